"""The wide learning bench in one table: per set, the shipped network minus the untrained one and minus greedy,
with the repairs and as placers alone, in final energy and constraints met (95 % bootstrap intervals over plans).
Reads <set>/results.json beside this script (h3ds bench plan2place --dataset D --n N --seeds 3 --out <set>);
writes summary.md: python app/bench/results/plan2place/learning/wide/summary.py"""

import json
from pathlib import Path

import numpy as np

from app.bench.paired import cell, interval, paired

HERE = Path(__file__).parent
SETS = ("seen", "human", "unseen_a", "unseen_b", "dense")
TRAINED, UNTRAINED, GREEDY = "plan2place (2880 ep)", "plan2place_untrained", "greedy"
BARE = ", no repair"
METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2))


def main() -> str:
    rng = np.random.default_rng(0)
    pairs = [(TRAINED, UNTRAINED), (TRAINED, GREEDY), (TRAINED + BARE, UNTRAINED + BARE), (TRAINED + BARE, GREEDY + BARE)]
    lines = []
    for metric, scale, up, digits in METRICS:
        lines += [f"**{metric}** ({'higher' if up else 'lower'} is better), shipped network minus ...", "",
                  "| set (plans) | - untrained | - greedy | placers alone: - untrained | placers alone: - greedy |",
                  "| --- | --- | --- | --- | --- |"]
        for s in SETS:
            rows = json.loads((HERE / s / "results.json").read_text())
            n = len({r["plan"] for r in rows})
            cells = [cell(*(scale * v for v in interval(paired(rows, metric, a, b), rng)), up, digits) for a, b in pairs]
            lines.append(f"| `{s}` ({n}) | " + " | ".join(cells) + " |")
        lines.append("")
    return "\n".join(lines)


if __name__ == "__main__":
    text = main()
    (HERE / "summary.md").write_text(text)
    print(text)
