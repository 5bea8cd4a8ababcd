"""Read after decision.md's outcome (and decision2.md's, with `2`), from the stored fresh[2]-rows.json (no new runs):
the learning proof's pairs on the fresh plans, the repair-reward checkpoint and the shipped weights each against
greedy and the untrained network.

    PYTHONPATH=. python app/bench/results/plan2place/repair-reward/proof.py [2]   # -> proof.md / proof2.md
"""

import json
import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import paired_lines  # noqa: E402

METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2), ("key_nav", 100, True, 2),
           ("cnt", 100, True, 2))
tag = sys.argv[1] if len(sys.argv) > 1 else ""
rows = json.loads((HERE / f"fresh{tag}-rows.json").read_text())
sets = "fresh2.py's plans" if tag else "decision.md's fresh plans (`human`: none at this offset)"
pairs = [(a, b) for a in ("repair-ep-1500", "plan2place") for b in ("greedy", "plan2place_untrained")]
lines = [f"The learning proof on {sets}, each minus the baseline, 95 % plan-bootstrap interval; bold: better, "
         "italic: worse, clear of 0", "", *paired_lines([r for r in rows if tag or r["set"] != "human"], pairs, METRICS)]
(HERE / f"proof{tag}.md").write_text("\n".join(lines) + "\n")
print("\n".join(lines))
