"""Alternating A/B timing of Plan2Place: each (plan, seed) solved by the tree as it is and by a variant, the order of the
two alternating per run, in one process; prints both p50s and means (ms per object) and how many layouts are
identical. A variant is a module in `variants/` with `old()` and `new()`, which patch the tree into each state.
Run from a tree's root: PYTHONPATH=.:app/bench/results/plan2place/speed python app/bench/results/plan2place/speed/alternate.py dense 20 2 variants.relation_met"""
import sys, time, importlib, numpy as np
from app.bench.plan2place import pick_records
from models.placement.base import get_solver
ds, n, seeds, variant = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
mod = importlib.import_module(variant)
plans = [r.plan for r in pick_records(ds, n)]
s = get_solver("plan2place"); s.solve(plans[0], seed=0)
T = {"old": [], "new": []}; same = 0; runs = 0
for seed in range(seeds):
    for i, p in enumerate(plans):
        out = {}
        for v in (("old", "new") if (i + seed) % 2 == 0 else ("new", "old")):
            (mod.old if v == "old" else mod.new)()
            t = time.perf_counter(); lay = s.solve(p, seed=seed); dt = time.perf_counter() - t
            T[v].append(1000 * dt / len(p.objects)); out[v] = lay.model_dump(exclude={"timing"})
        runs += 1; same += out["old"] == out["new"]
mod.new()
print(ds, "runs", runs, "identical", same)
for v in T: print(v, "p50 %.2f mean %.2f" % (np.median(T[v]), np.mean(T[v])))
print("ratio p50 new/old %.3f mean %.3f" % (np.median(T["new"]) / np.median(T["old"]), np.mean(T["new"]) / np.mean(T["old"])))
