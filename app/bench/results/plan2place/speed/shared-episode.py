"""The second solve sharing the first one's plan-only parts (`Episode(..., shares=)`: the problem, the candidates' geometry, the
reach grid) against making them again: per-object solve time, the two variants alternating per run in one process,
and whether the layouts are identical. Run from a tree's root:
PYTHONPATH=. python app/bench/results/plan2place/speed/shared-episode.py unseen_a 20 2"""
import sys, time, numpy as np
from app.bench.plan2place import pick_records
from models.placement import greedy as G
from models.placement.base import get_solver
ds = sys.argv[1]; n = int(sys.argv[2]); seeds = int(sys.argv[3])
plans = [r.plan for r in pick_records(ds, n)]
s = get_solver("plan2place"); s.solve(plans[0], seed=0)
orig = G.Episode.__init__
def no_share(self, plan, fixed=None, first=(), shares=None):
    orig(self, plan, fixed, first, None)
T = {"old": [], "new": []}; same = 0; runs = 0
for seed in range(seeds):
    for i, p in enumerate(plans):
        out = {}
        for v in (("old", "new") if (i + seed) % 2 == 0 else ("new", "old")):
            G.Episode.__init__ = no_share if v == "old" else orig
            t = time.perf_counter(); lay = s.solve(p, seed=seed); dt = time.perf_counter() - t
            T[v].append(1000 * dt / len(p.objects)); out[v] = lay.model_dump(exclude={"timing"})
        runs += 1; same += out["old"] == out["new"]
G.Episode.__init__ = orig
print(ds, "runs", runs, "identical", same)
for v in T: print(v, "p50 %.2f mean %.2f" % (np.median(T[v]), np.mean(T[v])))
print("ratio p50 new/old %.3f mean %.3f" % (np.median(T["new"]) / np.median(T["old"]), np.mean(T["new"]) / np.mean(T["old"])))
