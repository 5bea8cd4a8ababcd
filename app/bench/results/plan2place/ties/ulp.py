"""How many layouts a change of one unit in the last place (ulp) of the candidates' energy totals changes: each run
solved as is, then again with every total `CandidateEnergy.score` returns moved one ulp up, down or not (at random,
seeded): what another order of summation or another CPU's maths can do. Run from a tree's root:
PYTHONPATH=. python app/bench/results/plan2place/ties/ulp.py 20 plan2place,greedy   (plans per set, solvers)"""
import sys
import numpy as np
from app.bench.placement import pick_records
from models.placement.base import get_solver
from models.energy.vectorised import CandidateEnergy

score, noise = CandidateEnergy.score, {"rng": None}


def one_ulp_off(self, obj, cands, *args, **kwargs):
    terms = score(self, obj, cands, *args, **kwargs)
    if noise["rng"] is not None:
        way = noise["rng"].integers(-1, 2, len(terms["total"]))
        terms["total"] = np.where(way == 0, terms["total"], np.nextafter(terms["total"], np.where(way > 0, np.inf, -np.inf)))
    return terms


CandidateEnergy.score = one_ulp_off
poses = lambda layout: sorted((p.id, p.x, p.z, p.rotation) for p in layout.placements)  # noqa: E731
for solver in sys.argv[2].split(","):
    g = get_solver(solver)
    for ds in ("seen", "unseen_a", "unseen_b", "dense", "human"):
        changed = n = 0
        for seed in range(2):
            for r in pick_records(ds, int(sys.argv[1])):
                noise["rng"] = None
                a = poses(g.solve(r.plan, seed=seed))
                noise["rng"] = np.random.default_rng(seed)
                changed += a != poses(g.solve(r.plan, seed=seed))
                n += 1
        print(solver, ds, f"{changed}/{n} layouts changed by a 1-ulp change", flush=True)
