"""The energy floor's navigation term, in-process A/B on a set's bench plans (2 seeds), the two variants alternating:
`old`, the floor without it (navigation at least 0), checked once before the objects making way are placed again;
`new`, the floor with the task objects already cut off from the robot, checked before each of them is placed (also
in the group moves). Prints CPU time per object, how many times the energy scored candidates, and whether the
layouts are the same. Run from a tree's root:
PYTHONPATH=. python app/bench/results/plan2place/speed/nav-floor.py dense 20 6   (set, plans, rounds)"""
import sys, time, math
import numpy as np
from app.bench.plan2place import pick_records
from models.placement.base import get_solver
from models.placement import polish as P, groups as G
from models.energy.vectorised import CandidateEnergy
from models.energy.weights import WEIGHTS
new_floor, new_place_again = CandidateEnergy.floor, P._place_again
def old_floor(self, complete):
    missing = sum(o.id not in complete.poses for o in self.problem.plan.objects) / max(self.n_objects, 1)
    return (WEIGHTS["rel"] * math.log1p(self.rel_sum / max(complete.rel_n, 1))
            + WEIGHTS["collision"] * math.log1p(self.collision_sum) + WEIGHTS["oob"] * math.log1p(self.oob_sum)
            + WEIGHTS["aff"] * self.aff_sum / max(len(complete.zones), 1) + WEIGHTS["missing"] * missing)
def old_place_again(ep, movers, energy, placed, memo, why, within):
    first = [True]
    def once(e):
        if first[0]:
            first[0] = False; return within(e)
        return True
    return new_place_again(ep, movers, energy, placed, memo, why, once)
def use(v):
    CandidateEnergy.floor = old_floor if v == "old" else new_floor
    P._place_again = G._place_again = old_place_again if v == "old" else new_place_again
ds, n, reps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
plans = [r.plan for r in pick_records(ds, n)]
s = get_solver("plan2place"); s.solve(plans[0], seed=0)
calls = {"n": 0}; score = CandidateEnergy.score
def counted(self, obj, cands, *a, **k):
    calls["n"] += 1; return score(self, obj, cands, *a, **k)
CandidateEnergy.score = counted
tot = {"old": [], "new": []}; lay = {}
for r in range(reps):
    for v in ("old", "new") if r % 2 == 0 else ("new", "old"):
        use(v); calls["n"] = 0; objs = 0; t = time.process_time(); out = []
        for seed in range(2):
            for p in plans:
                l = s.solve(p, seed=seed); objs += len(p.objects); out.append([(q.id, q.x, q.z, q.rotation) for q in l.placements])
        tot[v].append(1000 * (time.process_time() - t) / objs); lay.setdefault(v, out); assert lay[v] == out
        print(v, round(tot[v][-1], 2), "ms/obj (CPU)", calls["n"], "energy scorings", flush=True)
print(ds, "same layouts:", lay["old"] == lay["new"], {v: round(float(np.median(x)), 2) for v, x in tot.items()},
      "new/old per pair:", [round(b / a, 3) for a, b in zip(tot["old"], tot["new"])])
