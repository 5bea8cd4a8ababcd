"""Why task objects are out of reach on `dense` after Plan2Place (Key_NAV 80 there against >= 95 asked): for each
task object out of reach, whether its access strip is covered or cut off and whether taking one other object away
would reach it; then whether the object itself has a legal pose (strict, or with front clearances relaxed, the
others where they are) from which the robot reaches it, and at which rank in energy. 20 diagnosis plans
(i % step == step // 2) x 2 seeds. From the root: PYTHONPATH=. python app/bench/results/plan2place/keynav-dense.py"""
import numpy as np
from collections import Counter
from models.datasets import load_dataset
from models.placement.base import get_solver
from models.placement.greedy import Episode
from models.placement.reach import Reach
from models.energy import navigation as nav
recs = load_dataset("dense")
step = max(len(recs) // 20, 1)
off = [r for i, r in enumerate(recs) if i % step == step // 2][:20]
sol = get_solver("plan2place")
c = Counter(); tasks = 0
for i, r in enumerate(off):
    for seed in (0, 1):
        lay = sol.solve(r.plan, seed=seed)
        ep = Episode(r.plan)
        placed = [ep.scorer.place(r.plan.object(p.id), p.x, p.z, p.rotation) for p in lay.placements]
        reach = ep.reach
        task = [o.id for o in r.plan.objects if o.is_task]
        tasks += len(task)
        pids = {p.id for p in placed}
        out = reach.unreachable(placed)
        for t in task:
            if t not in pids:
                c["left out"] += 1
        for t in out:
            p = next(q for q in placed if q.id == t)
            strip = reach.strip(p)
            # strip free at all (ignoring connectivity)?
            blocked = reach.blocked(placed)
            if not (strip & ~blocked).any():
                # which single removal frees a reachable strip cell
                ok = [q.id for q in placed if q.id != t and t not in reach.unreachable([x for x in placed if x is not q])]
                c["strip covered; one removal fixes" if ok else "strip covered; no single removal fixes"] += 1
            else:
                ok = [q.id for q in placed if q.id != t and t not in reach.unreachable([x for x in placed if x is not q])]
                c["strip free but cut off; one removal fixes" if ok else "strip free but cut off; no single removal"] += 1
            # is the door itself reachable?
            reachable = nav.reachable_from(blocked, reach.start)
            if reachable.sum() < 0.1 * (~blocked).sum():
                c["  (door region tiny)"] += 1
print("task objects", tasks, dict(c))

# second part: could the task object itself move to a reachable legal pose? at which energy rank?
from models.placement.moves import legal_poses
from models.energy.vectorised import CandidateEnergy
from models.geometry import SweptBoxes
c2 = Counter(); ranks = []
for i, r in enumerate(off):
    for seed in (0, 1):
        lay = sol.solve(r.plan, seed=seed)
        ep = Episode(r.plan)
        placed = [ep.scorer.place(r.plan.object(p.id), p.x, p.z, p.rotation) for p in lay.placements]
        reach = ep.reach
        for t in reach.unreachable(placed):
            obj = r.plan.object(t)
            others = [q for q in placed if q.id != t]
            cands, body = ep.scorer.bodies(obj)
            for relax_name, strict in (("strict", True), ("relaxed", False)):
                from models.placement.greedy import hard_filter
                ok = np.flatnonzero(hard_filter(ep.scorer, obj, others, cands, SweptBoxes(body), strict)[0])
                if not len(ok):
                    c2[f"{relax_name}: no legal pose"] += 1
                    continue
                terms = CandidateEnergy(ep.problem, others).score(obj, cands[ok])
                order = np.argsort(terms["total"], kind="stable")
                base = reach.blocked(others)
                good = None
                for rank, k in enumerate(order):
                    pose = ep.scorer.place(obj, *(float(v) for v in cands[ok[k]]))
                    if t not in reach.unreachable([*others, pose], nav.blocked_with(reach.mesh, base, pose.body)):
                        good = rank; break
                c2[f"{relax_name}: reachable pose {'none' if good is None else ('<40' if good < 40 else '>=40')}"] += 1
                if good is not None: ranks.append((relax_name, good, len(ok)))
print(dict(c2)); print(ranks)
