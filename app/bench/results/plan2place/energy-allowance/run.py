"""The energy allowance (0.05 per polish move) against none, Plan2Place and greedy, on the plans `decision.md` names,
the two variants' order alternating from run to run in one process; writes `runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/energy-allowance/run.py
"""
import json
import sys
import time
from pathlib import Path

import numpy as np

import models.placement.polish as polish
from app.bench.paired import cell, header, interval, paired
from app.bench.placement import score
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans
from models.placement.base import get_solver

sys.path.insert(0, str(Path(__file__).parents[1] / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

HERE = Path(__file__).parent
TAG, ALLOWANCE = "energy-allowance", 0.05
METRICS = (("constraint_satisfaction", 100, True, 2), ("cnt", 100, True, 2), ("key_nav", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3), ("pto_ms", 1, False, 2))
VARIANTS = {"none": 0.0, "allowance": ALLOWANCE}


def plan_sets() -> dict[str, tuple[list, range]]:
    held = {p.id for p in diagnosis_plans("human", 16)}
    human = [r.plan for r in load_dataset("human") if r.plan.id not in held]
    sizes = {"dense": 48, "unseen_a": 48, "seen": 24, "unseen_b": 24}
    return {**{ds: (fresh_plans(ds, TAG, n), range(5)) for ds, n in sizes.items()}, "human": (human, range(2))}


def run() -> list[dict]:
    rows, k, shipped = [], 0, polish.ALLOWANCE
    for label, (plans, seeds) in plan_sets().items():
        print(label, len(plans), "plans", file=sys.stderr, flush=True)
        for name in ("plan2place", "greedy"):
            solver = get_solver(name)
            for plan in plans:
                for seed in seeds:
                    k += 1
                    for variant in list(VARIANTS)[::1 if k % 2 else -1]:
                        polish.ALLOWANCE = VARIANTS[variant]
                        t = time.perf_counter()
                        layout = solver.solve(plan, seed=seed)
                        ms = 1000 * (time.perf_counter() - t) / len(plan.objects)
                        got = score(plan, layout)
                        rows.append({**{m: got.get(m) for m, *_ in METRICS if m != "pto_ms"}, "pto_ms": ms,
                                     "set": label, "placer": name, "solver": variant, "plan": plan.id, "seed": seed})
    polish.ALLOWANCE = shipped
    return rows


def report(rows: list[dict]) -> str:
    rng = np.random.default_rng(0)
    lines = [f"Allowance {ALLOWANCE} - none, mean over the same (plan, seed) runs [95 % bootstrap interval over plans]; "
             "metrics x 100, energy as is, PTO in ms per object (the two alternating in one process); **bold** = "
             "better with the interval clear of 0, _italic_ = worse.", "", *header("set / placer", METRICS)]
    for label in dict.fromkeys(r["set"] for r in rows):
        for placer in ("plan2place", "greedy"):
            mine = [r for r in rows if r["set"] == label and r["placer"] == placer]
            cells = [cell(*(sc * v for v in interval(paired(mine, m, "allowance", "none"), rng)), up, d)
                     for m, sc, up, d in METRICS]
            lines.append(f"| {label} / {placer} ({len(mine) // 2} runs) | " + " | ".join(cells) + " |")
    lines.append("")
    for label in dict.fromkeys(r["set"] for r in rows):
        mine = [r for r in rows if r["set"] == label and r["placer"] == "plan2place"]
        p50 = {v: float(np.median([r["pto_ms"] for r in mine if r["solver"] == v])) for v in VARIANTS}
        lines.append(f"- {label}, Plan2Place PTO p50: " + ", ".join(f"{v} {ms:.2f} ms" for v, ms in p50.items())
                     + f" ({100 * (p50['allowance'] / p50['none'] - 1):+.1f} %)")
    return "\n".join(lines) + "\n"


def main() -> None:
    rows = run()
    text = report(rows)
    for name, body in (("runs.json", json.dumps(rows)), ("result.md", text)):
        (HERE / name).write_text(body)
    print(text)


if __name__ == "__main__":
    main()
