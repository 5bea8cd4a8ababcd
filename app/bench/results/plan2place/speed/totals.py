"""Total CPU seconds of Plan2Place and DFS over 20 `unseen_a` bench plans x 2 seeds, best of 3 rounds, in one
process: a change too small for the speed bench's p50 shows here. Run from a tree's root (PYTHONPATH=.)."""
import sys
import time

import torch

from app.bench.placement import pick_records
from models.placement import get_solver

torch.set_num_threads(1)
ds = sys.argv[1] if len(sys.argv) > 1 else "unseen_a"
plans = [r.plan for r in pick_records(ds, 20)]
solvers = {"plan2place": get_solver("plan2place"), "dfs": get_solver("dfs")}
for s in solvers.values():
    s.solve(plans[0], seed=0)
best = {}
for _ in range(3):
    for name, solver in solvers.items():
        t = time.process_time()
        for seed in range(2):
            for p in plans:
                solver.solve(p, seed=seed)
        best[name] = min(best.get(name, float("inf")), time.process_time() - t)
print(ds, {k: round(v, 3) for k, v in best.items()}, "plan2place / dfs", round(best["plan2place"] / best["dfs"], 3))
