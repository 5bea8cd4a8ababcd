"""Diagnosis for decision.md: how often counting left-out objects as broken changes a layout (old and new first_ids in
turn). PYTHONPATH=. python app/bench/results/plan2place/left-out-broken/diagnose.py human 120"""
import sys
import numpy as np
from models.datasets import load_dataset
from models.placement import reorder as RO
from models.placement.result import NO_ROOM
from models.placement.base import get_solver
from app.bench.placement import score
def new_first(ep):
    objects = ep.problem.constraints.objects
    ids = set(RO.broken(ep)) | {oid for oid, why in ep.failed.items() if why == NO_ROOM}
    ids |= {c.target for oid in list(ids) if oid in objects for c in objects[oid].relations}
    return [o.id for o in ep.problem.plan.objects if o.id in ids and o.id not in ep.problem.fixed]
def old_first(ep):
    objects, ids = ep.problem.constraints.objects, set(RO.broken(ep))
    ids |= {c.target for oid in list(ids) for c in objects[oid].relations}
    return [o.id for o in ep.problem.plan.objects if o.id in ids and o.id not in ep.problem.fixed]
ds = sys.argv[1]; n = int(sys.argv[2])
recs = load_dataset(ds, "validation" if ds == "seen" else None)[:n]
s = get_solver(sys.argv[3] if len(sys.argv) > 3 else "plan2place")
changed, d = 0, {m: [] for m in ("cnt", "constraint_satisfaction", "energy", "key_nav")}
for r in recs:
    for seed in range(2):
        out = {}
        for name, f in (("old", old_first), ("new", new_first)):
            RO.first_ids = f
            lay = s.solve(r.plan, seed=seed)
            out[name] = (lay, score(r.plan, lay))
        RO.first_ids = old_first
        if [(p.id, p.x, p.z, p.rotation) for p in out["old"][0].placements] != [(p.id, p.x, p.z, p.rotation) for p in out["new"][0].placements]:
            changed += 1
            print(" changed", r.plan.id, seed, {m: round(out["new"][1][m] - out["old"][1][m], 3) for m in d if out["new"][1][m] is not None and out["old"][1][m] is not None}, flush=True)
        for m in d:
            if out["new"][1][m] is not None and out["old"][1][m] is not None:
                d[m].append(out["new"][1][m] - out["old"][1][m])
print(ds, "runs", len(recs) * 2, "changed", changed, {m: round(float(np.mean(v)), 4) for m, v in d.items()})
