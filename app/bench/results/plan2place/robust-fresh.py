"""Plans no one had placed do not crash or stall Plan2Place: 40 fresh plans per generated set (models.datasets.fresh,
tag robust-1127) x 2 seeds; counts errors, objects neither placed nor given a reason, objects left out, and the worst
time per object. Run from a tree's root: PYTHONPATH=. python app/bench/results/plan2place/robust-fresh.py"""
import time, traceback
from models.datasets.fresh import fresh_plans
from models.placement.base import get_solver
s = get_solver("plan2place")
for ds in ("seen", "unseen_a", "unseen_b", "dense"):
    plans = fresh_plans(ds, "robust-1127", 40)
    worst, bad, errors, left = 0.0, [], 0, 0
    for p in plans:
        for seed in (0, 1):
            t = time.perf_counter()
            try:
                lay = s.solve(p, seed=seed)
            except Exception:
                errors += 1; traceback.print_exc(); continue
            ms = 1000 * (time.perf_counter() - t) / len(p.objects)
            worst = max(worst, ms)
            placed = {o.id for o in lay.placements}
            un = {u.id: u.reason for u in lay.unplaced}
            for o in p.objects:
                if o.id not in placed and not un.get(o.id):
                    bad.append((p.id, seed, o.id))
            left += len(un)
    print(ds, len(plans), "plans; errors", errors, "objects neither placed nor reasoned", len(bad), bad[:3], "left out", left, "worst ms/obj", round(worst, 1), "max objects", max(len(p.objects) for p in plans), flush=True)
