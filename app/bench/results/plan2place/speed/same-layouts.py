"""Layouts of greedy and plan2place on 16 off-sample plans per set, dumped to JSON, to compare two trees' code:
(cd OLD && PYTHONPATH=. python same-layouts.py old.json 16); PYTHONPATH=. python same-layouts.py new.json 16; then compare the files."""
import sys, json, time
from models.datasets import load_dataset
from models.placement.base import get_solver
out = {}; T = {}
for ds in ("seen", "unseen_a", "unseen_b", "dense", "human"):
    recs = load_dataset(ds, "validation" if ds == "seen" else None)
    step = max(len(recs) // 20, 1)
    off = [r for i, r in enumerate(recs) if i % step == step // 2][:int(sys.argv[2])]
    for s in ("greedy", "plan2place"):
        sol = get_solver(s); t = time.process_time(); k = 0
        for i, r in enumerate(off):
            lay = sol.solve(r.plan, seed=i % 2)
            out[f"{ds}/{s}/{i}"] = sorted((p.id, round(p.x, 6), round(p.z, 6), p.rotation) for p in lay.placements)
            k += len(r.plan.objects)
        T[f"{ds}/{s}"] = round(1000 * (time.process_time() - t) / k, 2)
json.dump(out, open(sys.argv[1], "w"))
print(T)
