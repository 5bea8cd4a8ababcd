"""Each target's verdict on the 20-plan sample a set was benched on before, and on its larger run that replaced it
(status.py's verdicts on both; `seen` 100 plans, `human` all 120 rooms, `unseen_a`, `unseen_b`, `dense` 100 plans).
The samples are kept in seen-100/sample-20, human-all/sample-20 and <set>-sample-20 here. Reads those and
app/bench/results/placement-*/results.json, writes compare.md beside this script:
PYTHONPATH=. python app/bench/results/plan2place/larger-samples/compare.py"""

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from status import HEAD, plans, verdicts  # noqa: E402 (beside this directory)
from targets import RESULTS, SETS  # noqa: E402

SAMPLES = {"seen": HERE.parent / "seen-100" / "sample-20", "human": HERE.parent / "human-all" / "sample-20",
           **{s: HERE / f"{s}-sample-20" for s in ("unseen_a", "unseen_b", "dense")}}


def main() -> str:
    lines = ["Each target's verdict for Plan2Place (status.py) on the 20-plan sample of each set and on the larger run "
             "that replaced it (5 seeds each); a cell reads `sample -> larger run` where the verdict word changed.", "",
             "| set | plans | " + " | ".join(HEAD) + " |", "| --- | --- |" + " --- |" * len(HEAD)]
    for s in SETS:
        small = json.loads((SAMPLES[s] / "results.json").read_text())
        large = json.loads((RESULTS / f"placement-{s}" / "results.json").read_text())
        before, after = verdicts(small, np.random.default_rng(0)), verdicts(large, np.random.default_rng(0))
        cells = [a if b.split(" (")[0] == a.split(" (")[0] else f"**{b} -> {a}**" for b, a in zip(before, after)]
        lines.append(f"| {s} | {plans(small)} -> {plans(large)} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    text = main()
    (HERE / "compare.md").write_text(text)
    print(text)
