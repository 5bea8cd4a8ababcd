"""The energy allowance (0.05 per polish move) against none, Plan2Place and greedy, on the plans `decision.md` names,
the two variants' order alternating from run to run in one process; writes `runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/energy-allowance/run.py

It ran before the polish's second round in crowded rooms (`second-round/`); re-run now, its `dense` rows would
include that round in both variants.
"""
import sys
from pathlib import Path

import numpy as np

import models.placement.polish as polish
from app.bench.paired import alternating, header, store, variant_rows
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans

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
    return alternating(plan_sets(), polish, "ALLOWANCE", VARIANTS, METRICS)


def report(rows: list[dict]) -> str:
    lines = [f"Allowance {ALLOWANCE} - none, mean over the same (plan, seed) runs [95 % bootstrap interval over plans]; "
             "metrics x 100, energy as is, PTO in ms per object (the two alternating in one process); **bold** = "
             "better with the interval clear of 0, _italic_ = worse.", "", *header("set / placer", METRICS),
             *variant_rows(rows, "none", "allowance", METRICS)]
    lines.append("")
    for label in dict.fromkeys(r["set"] for r in rows):
        mine = [r for r in rows if r["set"] == label and r["placer"] == "plan2place"]
        p50 = {v: float(np.median([r["pto_ms"] for r in mine if r["solver"] == v])) for v in VARIANTS}
        lines.append(f"- {label}, Plan2Place PTO p50: " + ", ".join(f"{v} {ms:.2f} ms" for v, ms in p50.items())
                     + f" ({100 * (p50['allowance'] / p50['none'] - 1):+.1f} %)")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    runs = run()
    store(HERE, runs, report(runs))
