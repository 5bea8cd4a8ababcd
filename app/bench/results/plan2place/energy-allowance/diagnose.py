"""Would the polish meet more constraints if a move could raise the energy a little? A diagnosis on the diagnosis
plans (off the benchmark's samples; `lookahead-bound/run.py`'s `diagnosis_plans`), 16 per set x 2 seeds: Plan2Place
with the polish's allowance `polish.ALLOWANCE` at each value, paired against 0 (the code as it is), alternating in
one process. Writes `diagnose.md` and `diagnose.json` here.

    PYTHONPATH=. python app/bench/results/plan2place/energy-allowance/diagnose.py 0.02,0.05,0.15
"""
import json
import sys
import time
from pathlib import Path

import numpy as np

import models.placement.polish as polish
from app.bench.paired import cell, header, interval, paired
from app.bench.placement import score
from models.placement.base import get_solver

sys.path.insert(0, str(Path(__file__).parents[1] / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

HERE = Path(__file__).parent
SETS = ("seen", "human", "unseen_a", "unseen_b", "dense")
METRICS = (("constraint_satisfaction", 100, True, 2), ("realism", 100, True, 2), ("key_nav", 100, True, 2),
           ("cnt", 100, True, 2), ("energy", 1, False, 3), ("ms", 1, False, 2))


def run(allowances: list[float]) -> list[dict]:
    solver, rows, shipped = get_solver("plan2place"), [], polish.ALLOWANCE
    for ds in SETS:
        for plan in diagnosis_plans(ds, 16):
            for seed in (0, 1):
                for a in [0.0, *allowances]:
                    polish.ALLOWANCE = a
                    t = time.perf_counter()
                    layout = solver.solve(plan, seed=seed)
                    ms = 1000 * (time.perf_counter() - t) / len(plan.objects)
                    got = score(plan, layout)
                    rows.append({"set": ds, "plan": plan.id, "seed": seed, "solver": f"{a:g}", "ms": ms,
                                 **{m: got.get(m) for m, *_ in METRICS if m != "ms"}})
        print(ds, "done", file=sys.stderr, flush=True)
    polish.ALLOWANCE = shipped
    return rows


def report(rows: list[dict], allowances: list[float]) -> str:
    rng = np.random.default_rng(0)
    lines = ["Plan2Place with the polish's energy allowance - without (0), diagnosis plans, 16 per set x 2 seeds, "
             "mean [95 % bootstrap interval over plans]; metrics x 100, energy as is, ms per object", "",
             *header("set / allowance", METRICS)]
    for ds in SETS:
        mine = [r for r in rows if r["set"] == ds]
        for a in allowances:
            cells = [cell(*(sc * v for v in interval(paired(mine, m, f"{a:g}", "0"), rng)), up, d)
                     for m, sc, up, d in METRICS]
            lines.append(f"| {ds} / {a:g} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    values = [float(v) for v in sys.argv[1].split(",")]
    out = run(values)
    (HERE / "diagnose.json").write_text(json.dumps(out))
    (HERE / "diagnose.md").write_text(report(out, values))
    print(report(out, values))
