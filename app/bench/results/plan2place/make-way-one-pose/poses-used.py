import sys, time
from models.datasets import load_dataset
from models.placement.base import get_solver
from models.placement import polish
for ds in sys.argv[1:]:
    recs = load_dataset(ds, "validation" if ds == "seen" else None)
    step = max(len(recs) // 20, 1)
    off = [r for i, r in enumerate(recs) if i % step == step // 2][:20]
    polish.COUNT.clear()
    sol = get_solver("plan2place")
    for r in off:
        for seed in (0, 1):
            sol.solve(r.plan, seed=seed)
    print(ds, dict(sorted(polish.COUNT.items())))
