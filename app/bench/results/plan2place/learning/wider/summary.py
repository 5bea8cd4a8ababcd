"""The learning bench on more plans, read by the rule of decision.md: per set, the shipped network with the repairs
minus its untrained self and minus greedy (and the placers alone), in final energy and constraints met, on the
pooled sample (../wide's plans and the new ones of run.py) and on the new plans alone; then the rule's verdict.
Writes summary.md: python app/bench/results/plan2place/learning/wider/summary.py"""

import gzip
import json
from pathlib import Path

import numpy as np

from app.bench.paired import cell, interval, paired

HERE = Path(__file__).parent
WIDE = HERE.parent / "wide"
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")  # human: more seeds, no more rooms
TRAINED, UNTRAINED, GREEDY = "plan2place (2880 ep)", "plan2place_untrained", "greedy"
BARE = ", no repair"
METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2))


def new_rows(dataset: str) -> list[dict]:
    files = sorted((HERE / dataset).glob("results-*.json.gz"))
    return [r for f in files for r in json.loads(gzip.decompress(f.read_bytes()))]


def bootstrap(diffs: dict) -> tuple[float, float, float]:
    """`interval` with draws of its own (seed 0), so that a cell does not depend on the cells computed before it."""
    return interval(diffs, np.random.default_rng(0))


def beats(rows: list[dict], new: list[dict], metric: str, up: bool) -> bool:
    """The rule: both pooled intervals clear of 0 in the trained network's favour, both new-plan means the same way."""
    sign = 1 if up else -1
    for base in (UNTRAINED, GREEDY):
        _, lo, hi = (sign * v for v in bootstrap(paired(rows, metric, TRAINED, base)))
        mean_new = sign * bootstrap(paired(new, metric, TRAINED, base))[0]
        if min(lo, hi) <= 0 or not mean_new > 0:
            return False
    return True


def main() -> str:
    pairs = [(TRAINED, UNTRAINED), (TRAINED, GREEDY),
             (TRAINED + BARE, UNTRAINED + BARE), (TRAINED + BARE, GREEDY + BARE)]
    lines, verdicts = [], []
    for metric, scale, up, digits in METRICS:
        lines += [f"**{metric}** ({'higher' if up else 'lower'} is better), shipped network minus ...", "",
                  "| set (plans) | sample | - untrained | - greedy | placers alone: - untrained | "
                  "placers alone: - greedy |",
                  "| --- | --- | --- | --- | --- | --- |"]
        for s in SETS:
            new = new_rows(s)
            if not new:
                continue
            pooled = json.loads((WIDE / s / "results.json").read_text()) + new
            alone = "new seeds alone" if s == "human" else "new plans alone"
            for label, rows in (("pooled", pooled), (alone, new)):
                n = len({r["plan"] for r in rows})
                cells = [cell(*(scale * v for v in bootstrap(paired(rows, metric, a, b))), up, digits)
                         for a, b in pairs]
                lines.append(f"| `{s}` ({n}) | {label} | " + " | ".join(cells) + " |")
            won = beats(pooled, new, metric, up)
            verdicts.append(f"- `{s}`, {metric}: the full placer {'beats both' if won else 'does not beat both'}")
        lines.append("")
    return "\n".join(lines + ["By the rule of decision.md:", ""] + verdicts) + "\n"


if __name__ == "__main__":
    text = main()
    (HERE / "summary.md").write_text(text)
    print(text)
