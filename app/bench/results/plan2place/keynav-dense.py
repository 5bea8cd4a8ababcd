"""Why task objects are out of reach on `dense` after Plan2Place (Key_NAV 80 there against >= 95 asked): for each
task object out of reach, whether its access strip is covered or cut off and whether taking one other object away
would reach it; then whether the object itself has a legal pose (strict, or with front clearances relaxed, the
others where they are) from which the robot reaches it, and at which rank in energy. 20 diagnosis plans
(i % step == step // 2) x 2 seeds. From the root: PYTHONPATH=. python app/bench/results/plan2place/keynav-dense.py"""
from collections import Counter

import numpy as np

from models.datasets import load_dataset
from models.energy import navigation as nav
from models.energy.vectorised import CandidateEnergy
from models.geometry import SweptBoxes
from models.placement.base import get_solver
from models.placement.greedy import Episode, hard_filter


def why_out(reach, placed, t: str) -> str:
    """Is the strip of out-of-reach task object `t` covered or cut off, and would taking one object away reach it?"""
    blocked = reach.blocked(placed)
    covered = not (reach.strip(next(q for q in placed if q.id == t)) & ~blocked).any()
    one = any(t not in reach.unreachable([x for x in placed if x is not q]) for q in placed if q.id != t)
    return (f"strip {'covered' if covered else 'free but cut off'}; "
            f"{'one removal fixes' if one else 'no single removal fixes'}")


def own_pose(ep, reach, placed, t: str, strict: bool) -> tuple[str, int | None]:
    """Has `t` a legal pose (the others where they are) from which the robot reaches it; its rank in energy."""
    obj, others = ep.problem.plan.object(t), [q for q in placed if q.id != t]
    cands, body = ep.scorer.bodies(obj)
    ok = np.flatnonzero(hard_filter(ep.scorer, obj, others, cands, SweptBoxes(body), strict)[0])
    if not len(ok):
        return "no legal pose", None
    order = np.argsort(CandidateEnergy(ep.problem, others).score(obj, cands[ok])["total"], kind="stable")
    base = reach.blocked(others)
    for rank, k in enumerate(order):
        pose = ep.scorer.place(obj, *(float(v) for v in cands[ok[k]]))
        if t not in reach.unreachable([*others, pose], nav.blocked_with(reach.mesh, base, pose.body)):
            return f"reachable pose {'<40' if rank < 40 else '>=40'}", rank
    return "reachable pose none", None


recs = load_dataset("dense")
step = max(len(recs) // 20, 1)
solver, tasks, strips, poses, ranks = get_solver("plan2place"), 0, Counter(), Counter(), []
for r in [r for i, r in enumerate(recs) if i % step == step // 2][:20]:
    for seed in (0, 1):
        ep = Episode(r.plan)
        placed = [ep.scorer.place(r.plan.object(p.id), p.x, p.z, p.rotation)
                  for p in solver.solve(r.plan, seed=seed).placements]
        tasks += sum(o.is_task for o in r.plan.objects)
        strips["left out"] += sum(o.is_task and o.id not in {p.id for p in placed} for o in r.plan.objects)
        for t in ep.reach.unreachable(placed):
            strips[why_out(ep.reach, placed, t)] += 1
            for name, strict in (("strict", True), ("relaxed", False)):
                found, rank = own_pose(ep, ep.reach, placed, t, strict)
                poses[f"{name}: {found}"] += 1
                if rank is not None:
                    ranks.append((name, rank))
print("task objects", tasks, dict(strips))
print(dict(poses))
print(ranks)
