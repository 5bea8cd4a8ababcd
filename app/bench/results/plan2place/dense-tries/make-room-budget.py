"""Tried for `dense`, not kept: make_room with more blockers / poses (MAX_BLOCKERS, TRIES), on 20 dense plans off the
benchmark sample; the shipped Plan2Place network, seed 0. Run from the repository root:
PYTHONPATH=. python app/bench/results/plan2place/dense-tries/make-room-budget.py > .../make-room-budget.txt"""
import sys, time
import numpy as np
from models.datasets import load_dataset
from models.placement import moves
from models.placement.plan2place.policy import place, shipped_policy, shipped_weights
recs = load_dataset("dense", None)
step = max(len(recs) // 20, 1)
off = [r for i, r in enumerate(recs) if i % step == step // 2][:20]
pol, ug = shipped_policy(), shipped_weights().use_global
for mb, tries in [(3, 5), (3, 20), (5, 5), (5, 20), (8, 40)]:
    moves.MAX_BLOCKERS = mb
    d = moves.displacements.__defaults__; moves.displacements.__defaults__ = d[:-1] + (tries,)
    out = 0; t = time.perf_counter(); E = []
    for r in off:
        ep = place(pol, r.plan, np.random.default_rng(0), ug); out += len(ep.failed); E.append(ep.energy)
    print(mb, tries, "left out", out, "s", round(time.perf_counter() - t, 1), "energy", round(float(np.mean(E)), 3), flush=True)
