"""Would a soft front clearance (blocked-fronts-soft.py's) be worth keeping in crowded rooms? Plan2Place normal and
soft on 40 `dense` plans off the bench's sample (i % 15 in {3, 7}), 2 seeds, each mode in its own process, then
paired (app.bench.paired). From the root:
python soft-clearance-dense.py normal; python soft-clearance-dense.py soft; python soft-clearance-dense.py pair > soft-clearance-dense.md"""
import sys, time, json
import numpy as np
mode = sys.argv[1]
OUT = "/tmp/soft-clearance-dense-{}.json"
if mode == "pair":
    from app.bench.paired import cell, interval, paired
    rows = json.load(open(OUT.format("normal"))) + json.load(open(OUT.format("soft")))
    rng = np.random.default_rng(0)
    print("| metric | normal | soft | soft - normal [95 % interval over plans] |\n| --- | --- | --- | --- |")
    for m, sc, up, d in [("energy", 1, False, 3), ("cnt", 100, True, 2), ("key_nav", 100, True, 2),
                         ("constraint_satisfaction", 100, True, 2), ("realism", 100, True, 2), ("nav", 100, True, 2),
                         ("strips", 1, False, 2), ("pto_s", 1000, False, 2)]:
        mean = {s: np.mean([r[m] for r in rows if r["solver"] == s and r.get(m) is not None]) * sc for s in ("normal", "soft")}
        diff = cell(*(sc * v for v in interval(paired(rows, m, "soft", "normal"), rng)), up, d)
        print(f"| {m} | {mean['normal']:.{d}f} | {mean['soft']:.{d}f} | {diff} |")
    sys.exit()
import importlib.util


def _script(name: str):
    spec = importlib.util.spec_from_file_location(name.replace("-", "_"), f"app/bench/results/plan2place/{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


if mode == "soft":
    _script("blocked-fronts-soft").soften()
from models.datasets import load_dataset
from models.placement.base import get_solver
from app.bench.placement import score
bf = _script("blocked-fronts")
recs = load_dataset("dense"); plans = [r.plan for i, r in enumerate(recs) if i % 15 in (3, 7)]
sol = get_solver("plan2place"); rows = []
for p in plans:
    for seed in (0, 1):
        t = time.perf_counter(); lay = sol.solve(p, seed=seed); dt = time.perf_counter() - t
        rows.append({**{k: v for k, v in score(p, lay).items() if isinstance(v, (int, float)) or v is None}, "plan": p.id, "seed": seed, "solver": mode, "strips": bf.blocked_strips(p, lay), "pto_s": dt / len(p.objects)})
json.dump(rows, open(OUT.format(mode), "w"))
print(mode, len(rows))
