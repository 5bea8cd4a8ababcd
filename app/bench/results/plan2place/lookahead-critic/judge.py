"""The rule of decision.md: checkpoints of fit.py against the shipped weights, every placer with the repairs.

    PYTHONPATH=. python app/bench/results/plan2place/lookahead-critic/judge.py select CKPT.npz ...  # -> selection.md
    PYTHONPATH=. python app/bench/results/plan2place/lookahead-critic/judge.py fresh CKPT.npz       # -> fresh.md
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from app.bench.paired import cell, interval, paired
from app.bench.placement import score
from models.placement.base import get_solver
from models.placement.plan2place.policy import NumpyPolicy, Weights
from models.placement.plan2place.solver import Plan2PlaceSolver, untrained_solver

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import SETS, diagnosis_plans  # noqa: E402  (lookahead-bound/run.py)

METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2), ("key_nav", 100, True, 2),
           ("cnt", 100, True, 2), ("realism", 100, True, 2))
SHIPPED = "plan2place"


def fresh_plans(ds: str) -> list:
    import importlib.util
    spec = importlib.util.spec_from_file_location("make_way_run", HERE.parent / "make-way-strips" / "run.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.plans(ds, "7/8")


def solvers(ckpts: list[Path], baselines: bool) -> list:
    out = [get_solver(SHIPPED)]
    for c in ckpts:
        w = Weights.load(c)
        out.append(Plan2PlaceSolver(NumpyPolicy(w.arrays, w.net), name=c.stem, use_global=w.use_global))
    return out + ([get_solver("greedy"), untrained_solver()] if baselines else [])


def run(plans_of, placers) -> list[dict]:
    rows = []
    for ds in SETS:
        for plan in plans_of(ds):
            for seed in (0, 1):
                for s in placers:
                    t = time.perf_counter()
                    layout = s.solve(plan, seed=seed)
                    ms = 1000 * (time.perf_counter() - t) / len(plan.objects)
                    got = score(plan, layout)
                    rows.append({"set": ds, "plan": plan.id, "seed": seed, "solver": s.name, "ms": ms,
                                 **{m: got[m] for m, *_ in METRICS}})
        print(ds, "done", flush=True)
    return rows


def table(rows: list[dict], names: list[str]) -> list[str]:
    rng = np.random.default_rng(0)
    lines = ["| set | solver | " + " | ".join(m for m, *_ in METRICS) + " | ms p50 |",
             "| --- | --- |" + " ---: |" * (len(METRICS) + 1)]
    for ds in SETS:
        for n in names:
            mine = [r for r in rows if r["set"] == ds and r["solver"] == n]
            lines.append(f"| {ds} | {n} | " + " | ".join(f"{sc * np.mean([r[m] for r in mine]):.{d}f}"
                                                      for m, sc, _, d in METRICS) +
                         f" | {np.median([r['ms'] for r in mine]):.1f} |")
    lines += ["", "Paired against the shipped weights (each minus shipped, 95 % plan-bootstrap interval; bold: better, "
              "italic: worse, clear of 0)", "", "| set | solver | " + " | ".join(m for m, *_ in METRICS) + " |",
              "| --- | --- |" + " --- |" * len(METRICS)]
    for ds in SETS:
        mine = [r for r in rows if r["set"] == ds]
        for n in names[1:]:
            cells = [cell(*(sc * v for v in interval(paired(mine, m, n, SHIPPED), rng)), up, d) for m, sc, up, d in METRICS]
            lines.append(f"| {ds} | {n} | " + " | ".join(cells) + " |")
    return lines


def means(rows, ds, name, metric) -> float:
    return float(np.mean([r[metric] for r in rows if r["set"] == ds and r["solver"] == name]))


def main(mode: str, ckpts: list[Path]) -> int:
    placers = solvers(ckpts, baselines=mode == "fresh")
    names = [s.name for s in placers]
    rows = run((lambda ds: diagnosis_plans(ds, 16)) if mode == "select" else fresh_plans, placers)
    (HERE / f"{mode}-rows.json").write_text(json.dumps(rows) + "\n")
    lines = table(rows, names)
    if mode == "select":
        def key(n):
            below = sum(means(rows, ds, n, "energy") < means(rows, ds, SHIPPED, "energy") for ds in SETS)
            return -below, np.mean([means(rows, ds, n, "energy") - means(rows, ds, SHIPPED, "energy") for ds in SETS])
        chosen = min((c.stem for c in ckpts), key=key)
        lines += ["", f"chosen by decision.md step 1: {chosen} (mean energy below the shipped weights' on "
                  f"{-key(chosen)[0]} of {len(SETS)} sets)"]
    else:
        n = ckpts[0].stem
        lower = sum(means(rows, ds, n, "energy") < means(rows, ds, SHIPPED, "energy") for ds in SETS)
        kept = all(means(rows, ds, n, "constraint_satisfaction") >= means(rows, ds, SHIPPED, "constraint_satisfaction")
                   - 0.005 and all(means(rows, ds, n, m) >= means(rows, ds, SHIPPED, m) for m in ("key_nav", "cnt"))
                   for ds in SETS)
        lines += ["", f"decision.md step 2: energy lower on {lower} of {len(SETS)} sets; constraints, Key_NAV and CNT "
                  f"kept: {kept}; ship: {lower >= 4 and kept}"]
    (HERE / f"{'selection' if mode == 'select' else 'fresh'}.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], [Path(p) for p in sys.argv[2:]]))
