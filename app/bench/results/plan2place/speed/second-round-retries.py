"""The polish's second round in crowded rooms tries again each object still broken once anything moved since its last
try. Can a cheap test tell which tries may find a move? For each second try on the diagnosis plans x 2 seeds: is
the object related (by a constraint) to an object moved since, the least distance from its pose to a moved
object's old or new pose, and whether a move was found. Run from a tree's root:
PYTHONPATH=. python app/bench/results/plan2place/speed/second-round-retries.py dense 20"""
import sys, time
import numpy as np
sys.path.insert(0, "app/bench/results/plan2place/lookahead-bound")
from run import diagnosis_plans
from models.placement import polish as P
from models.placement.base import get_solver
ds = sys.argv[1]; n = int(sys.argv[2])
plans = diagnosis_plans(ds, n)
s = get_solver("plan2place")
rows = []
def rel(ep, a, b):
    objs = ep.problem.constraints.objects
    r1 = a in objs and any(c.target == b for c in objs[a].relations)
    r2 = b in objs and any(c.target == a for c in objs[b].relations)
    return r1 or r2
def _round(ep, observer, moved, tried):
    now, before = P.Standing(ep), len(moved)
    for oid in P.broken(ep):
        if tried.get(oid) == len(moved):
            continue
        second = oid in tried
        snap = {p.id: p for p in ep.placed}
        if second:
            since = set(moved[tried[oid]:])
            last = poses_at[oid]
            cur = snap[oid]
            dists = []
            for m in since:
                for q in (last.get(m), snap.get(m)):
                    if q is not None:
                        dists.append(np.hypot(q.x - cur.x, q.z - cur.z))
            feat = dict(plan=ep.problem.plan.id, oid=oid, n_since=len(since), related=any(rel(ep, oid, m) for m in since),
                        mind=float(min(dists)) if dists else 99.0)
        tried[oid] = len(moved)
        poses_at[oid] = snap
        t = time.perf_counter()
        move = P._relocation(ep, now, oid)
        dt = time.perf_counter() - t
        if second:
            feat.update(ok=move is not None, ms=1000 * dt); rows.append(feat)
        if move is not None:
            now.take(move, moved, observer)
    return len(moved) > before
P._round = _round
poses_at = {}
for seed in (0, 1):
    for p in plans:
        poses_at.clear(); s.solve(p, seed=seed)
ok = [r for r in rows if r["ok"]]
print(len(rows), "attempts", len(ok), "ok", "ms total", round(sum(r["ms"] for r in rows)))
for th in (0.5, 1.0, 1.5, 2.0, 3.0):
    keep = [r for r in rows if r["related"] or r["mind"] < th]
    print("related or mind <", th, ":", len(keep), "tried", sum(r["ok"] for r in keep), "ok kept", round(sum(r["ms"] for r in keep)), "ms")
keep = [r for r in rows if r["related"]]
print("related only:", len(keep), sum(r["ok"] for r in keep), round(sum(r["ms"] for r in keep)))
