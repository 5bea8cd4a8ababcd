"""Plan2Place against DFS (the default solver before), paired on the placement bench's stored runs: for each
set and metric, the mean difference plan2place - dfs over the same (plan, seed) pairs and a 95 % bootstrap
interval over plans (plans resampled, their seeds kept together). Reads app/bench/results/placement-*/results.json,
writes default-choice.md beside this script: python app/bench/results/plan2place/default-choice.py"""

import json
from pathlib import Path

import numpy as np

from app.bench.paired import cell, interval, paired

RESULTS = Path(__file__).resolve().parents[1]
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
# metric, scale, whether higher is better
METRICS = (("cnt", 100, True), ("key_nav", 100, True), ("nav", 100, True), ("constraint_satisfaction", 100, True),
           ("realism", 100, True), ("energy", 1, False), ("pto", 1000, False))


def main() -> str:
    rng = np.random.default_rng(0)
    head = "| set | " + " | ".join(f"{m} ({'higher' if up else 'lower'} is better)" for m, _, up in METRICS) + " |"
    lines = ["Plan2Place - DFS, mean over the same (plan, seed) pairs, [95 % bootstrap interval over plans]; "
             "metrics x 100, energy as is, PTO in ms per object; **bold** = Plan2Place better with the interval "
             "clear of 0, _italic_ = worse with the interval clear of 0.", "", head,
             "| --- |" + " --- |" * len(METRICS)]
    for s in SETS:
        rows = json.loads((RESULTS / f"placement-{s}" / "results.json").read_text())
        cells = []
        for metric, scale, up in METRICS:
            cells.append(cell(*(scale * v for v in interval(paired(rows, metric, "plan2place", "dfs"), rng)), up))
        lines.append(f"| {s} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    text = main()
    (Path(__file__).parent / "default-choice.md").write_text(text)
    print(text)
