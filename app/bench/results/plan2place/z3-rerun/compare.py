"""Z3's rows of the placement bench before and after each solve got a Z3 context of its own (a642104): the runs before
came from bench workers whose shared context kept every earlier solve's state. Paired over the same (plan, seed) runs,
95 % bootstrap interval over plans (app.bench.paired). The rows before are read from git at BEFORE (the last commit
with them); writes compare.md beside this script:

    PYTHONPATH=. python app/bench/results/plan2place/z3-rerun/compare.py
"""
import json
import statistics
import subprocess
from pathlib import Path

import numpy as np

from app.bench.paired import cell, header, interval, paired

HERE = Path(__file__).parent
RESULTS = HERE.parents[1]
BEFORE = "a69ea43"
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
METRICS = (("cnt", 100, True, 2), ("key_nav", 100, True, 2), ("constraint_satisfaction", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3))


def rows_before(name: str) -> list[dict]:
    text = subprocess.run(["git", "show", f"{BEFORE}:app/bench/results/placement-{name}/results.json"],
                          capture_output=True, text=True, check=True, cwd=HERE).stdout
    return [{**r, "solver": "z3 before"} for r in json.loads(text) if r["solver"] == "z3"]


def main() -> str:
    rng = np.random.default_rng(0)
    lines = ["Z3 after minus Z3 before (each solve in a context of its own), the same (plan, seed) runs of the "
             "placement bench, mean [95 % bootstrap interval over plans]; metrics x 100, energy as is; **bold** = "
             "after better with the interval clear of 0, _italic_ = worse. Last columns: runs that placed nothing, "
             "and PTO p50 (ms per object), before -> after.", "",
             header("set", METRICS)[0] + " placed nothing | PTO p50 |",
             header("set", METRICS)[1] + " --- | --- |"]
    for name in SETS:
        now = [r for r in json.loads((RESULTS / f"placement-{name}" / "results.json").read_text())
               if r["solver"] == "z3"]
        old = rows_before(name)
        rows = now + old
        cells = [cell(*(scale * v for v in interval(paired(rows, m, "z3", "z3 before"), rng)), up, digits)
                 for m, scale, up, digits in METRICS]
        empty = [sum(not r["cnt"] for r in rs) for rs in (old, now)]
        p50 = [1000 * statistics.median(r["pto"] for r in rs) for rs in (old, now)]
        lines.append(f"| {name} | " + " | ".join(cells) + f" | {empty[0]} -> {empty[1]} | {p50[0]:.1f} -> {p50[1]:.1f} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    text = main()
    (HERE / "compare.md").write_text(text)
    print(text)
