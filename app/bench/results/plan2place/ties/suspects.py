"""The two greedy runs of the stored placement bench that no later solve reproduced (seen-04986 seed 1: energy 0.28760
stored; unseen_a-00225 seed 4: 0.03204 stored), and Plan2Place's on the same (plan, seed), each solved `reps` times with
every candidate total moved one ulp at random as in ulp.py (perturbation seeds 0..reps-1): the energies seen, with
how often. Run from a tree's root: PYTHONPATH=. python app/bench/results/plan2place/ties/suspects.py 20"""
import sys
from collections import Counter
import numpy as np
from app.bench.placement import pick_records, score
from models.placement.base import get_solver
from models.energy.vectorised import CandidateEnergy

score_candidates, noise = CandidateEnergy.score, {"rng": None}


def one_ulp_off(self, obj, cands, *args, **kwargs):
    terms = score_candidates(self, obj, cands, *args, **kwargs)
    way = noise["rng"].integers(-1, 2, len(terms["total"]))
    terms["total"] = np.where(way == 0, terms["total"], np.nextafter(terms["total"], np.where(way > 0, np.inf, -np.inf)))
    return terms


CandidateEnergy.score = one_ulp_off
for solver in ("greedy", "plan2place"):
    g = get_solver(solver)
    for ds, pid, seed in (("seen", "seen-04986", 1), ("unseen_a", "unseen_a-00225", 4)):
        plan = next(r.plan for r in pick_records(ds, 20) if r.plan.id == pid)
        seen = Counter()
        for k in range(int(sys.argv[1])):
            noise["rng"] = np.random.default_rng(k)
            seen[round(score(plan, g.solve(plan, seed=seed))["energy"], 5)] += 1
        print(solver, pid, "seed", seed, dict(seen.most_common()), flush=True)
