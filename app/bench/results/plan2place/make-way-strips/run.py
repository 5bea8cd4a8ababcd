"""Plan2Place and greedy on 24 plans per set off the bench samples (see decision.md), 2 seeds, in the tree on
PYTHONPATH; writes rows (metrics, plan, seed, solver) to the JSON file given. `python run.py pair OLD NEW` prints
the paired table (new - old). From a tree's root: PYTHONPATH=. python .../run.py /tmp/new.json [QUARTER]
(the plans at `i % step == QUARTER * step // 4`; 1 unless given: variants 1 and 2 used 1, variant 3 used 3;
a fraction N/D picks `i % step == N * step // D`: the exact baseline's decision used 3/8)"""
import json
import sys
import time

import numpy as np

SETS = ("seen", "unseen_a", "unseen_b", "human", "dense")
METRICS = (("constraint_satisfaction", 100, True, 2), ("key_nav", 100, True, 2), ("cnt", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3), ("pto_s", 1000, False, 2))


def plans(ds, quarter="1"):
    from app.bench.placement import pick_records
    from models.datasets import load_dataset
    recs = load_dataset(ds, "validation" if ds == "seen" else None)
    bench = {r.plan.id for n in ((20, 40) if ds == "seen" else (20,)) for r in pick_records(ds, n)}
    step = max(len(recs) // 20, 1)
    num, den = (int(v) for v in f"{quarter}/4".split("/")[:2])
    return [r.plan for i, r in enumerate(recs) if i % step == num * step // den and r.plan.id not in bench][:24]


def run(out, quarter="1"):
    from app.bench.placement import score
    from models.placement.base import get_solver
    rows = []
    for ds in SETS:
        for name in ("plan2place", "greedy"):
            solver = get_solver(name)
            for p in plans(ds, quarter):
                for seed in (0, 1):
                    t = time.perf_counter()
                    lay = solver.solve(p, seed=seed)
                    dt = time.perf_counter() - t
                    s = score(p, lay)
                    rows.append({**{m: s.get(m) for m, *_ in METRICS if m != "pto_s"}, "pto_s": dt / len(p.objects),
                                 "set": ds, "solver": name, "plan": p.id, "seed": seed})
    json.dump(rows, open(out, "w"))


def pair(old, new):
    from app.bench.paired import cell, header, interval, paired
    rng = np.random.default_rng(0)
    a, b = json.load(open(old)), json.load(open(new))
    lines = header("set / solver: new - old", METRICS)
    for ds in SETS:
        for name in ("plan2place", "greedy"):
            rows = [{**r, "solver": "old"} for r in a if r["set"] == ds and r["solver"] == name] + \
                   [{**r, "solver": "new"} for r in b if r["set"] == ds and r["solver"] == name]
            cells = [cell(*(sc * v for v in interval(paired(rows, m, "new", "old"), rng)), up, d) for m, sc, up, d in METRICS]
            lines.append(f"| {ds} / {name} ({len(rows) // 2} runs) | " + " | ".join(cells) + " |")
    print("\n".join(lines))


if __name__ == "__main__":
    pair(*sys.argv[2:4]) if sys.argv[1] == "pair" else run(sys.argv[1], *sys.argv[2:3])
