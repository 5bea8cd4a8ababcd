"""Which of its poses a successful make-way move of the polish took, and how many poses were tried, for Plan2Place
on the diagnosis plans (`i % step == step // 2`, 20 plans x 2 seeds per set). From the root:
PYTHONPATH=. python app/bench/results/plan2place/make-way-one-pose/poses-used.py seen unseen_a unseen_b human"""
import sys
from collections import Counter

import models.placement.polish as P
from models.datasets import load_dataset
from models.placement.base import get_solver

COUNT, offered = Counter(), []
displacements, relocation = P.displacements, P._relocation


def counted_displacements(ep, obj, cands, *args, **kwargs):
    out = displacements(ep, obj, cands, *args, **kwargs)
    offered[:] = [tuple(cands[i]) for i, _ in out]
    return out


def counted_relocation(ep, now, oid, poses=P.MAKE_WAY_POSES):
    offered.clear()
    move = relocation(ep, now, oid, poses)
    made_way = move is not None and len(move.steps) > 1  # a free move is one step
    k = offered.index((move.steps[0].x, move.steps[0].z, move.steps[0].rotation)) if made_way else None
    for j in range(len(offered) if k is None else k + 1):
        COUNT[f"tried {j}"] += 1
    if k is not None:
        COUNT[f"ok at {k}"] += 1
    return move


P.displacements, P._relocation = counted_displacements, counted_relocation
for ds in sys.argv[1:]:
    recs = load_dataset(ds, "validation" if ds == "seen" else None)
    step = max(len(recs) // 20, 1)
    COUNT.clear()
    solver = get_solver("plan2place")
    for r in [r for i, r in enumerate(recs) if i % step == step // 2][:20]:
        for seed in (0, 1):
            solver.solve(r.plan, seed=seed)
    print(ds, dict(sorted(COUNT.items())))
