"""Read after decision.md's outcome, from the stored fresh-rows.json (no new runs): the learning proof's pairs on the
fresh plans, the repair-reward checkpoint and the shipped weights each against greedy and the untrained network.

    PYTHONPATH=. python app/bench/results/plan2place/repair-reward/proof.py   # -> proof.md
"""

import json
import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import paired_lines  # noqa: E402

METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2), ("key_nav", 100, True, 2),
           ("cnt", 100, True, 2))
rows = json.loads((HERE / "fresh-rows.json").read_text())
pairs = [(a, b) for a in ("repair-ep-1500", "plan2place") for b in ("greedy", "plan2place_untrained")]
lines = ["The learning proof on decision.md's fresh plans (`human`: none at this offset), each minus the baseline, "
         "95 % plan-bootstrap interval; bold: better, italic: worse, clear of 0", "",
         *paired_lines([r for r in rows if r["set"] != "human"], pairs, METRICS)]
(HERE / "proof.md").write_text("\n".join(lines) + "\n")
print("\n".join(lines))
