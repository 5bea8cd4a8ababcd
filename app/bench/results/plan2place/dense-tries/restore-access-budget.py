"""Tried for `dense`, not kept: restore_access with more rounds / nearby objects / poses (ROUNDS, NEAR, CHECKS), on 20 dense
plans off the benchmark sample (PYTHONPATH=. python app/bench/results/plan2place/dense-tries/restore-access-budget.py dense 20)."""
import sys, time
import numpy as np
from models.datasets import load_dataset
from models.metrics import scene_metrics
from models.placement import repair as R
from models.placement.base import get_solver
ds = sys.argv[1]; n = int(sys.argv[2])
recs = load_dataset(ds, "validation" if ds == "seen" else None)
step = max(len(recs) // 20, 1)
off = [r for i, r in enumerate(recs) if i % step == step // 2][:n]
sol = get_solver("plan2place")
for rounds, near, checks in [(3, 4, 40), (6, 4, 40), (6, 8, 40), (6, 8, 120), (10, 12, 200)]:
    R.ROUNDS, R.NEAR, R.CHECKS = rounds, near, checks
    kn, cs, t, objs = [], [], 0.0, 0
    for i, r in enumerate(off):
        t0 = time.process_time(); lay = sol.solve(r.plan, seed=0); t += time.process_time() - t0
        m = scene_metrics(r.plan, lay); objs += len(r.plan.objects)
        if m.key_nav is not None: kn.append(m.key_nav)
        cs.append(m.constraint_satisfaction)
    print(rounds, near, checks, "key_nav", round(100 * np.mean(kn), 1), "cons", round(100 * np.mean(cs), 1), "ms/obj", round(1000 * t / objs, 2), flush=True)
