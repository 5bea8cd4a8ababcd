"""Is proof2.md's finding (the shipped weights above the untrained network in energy on `unseen_a`, on 24 new plans)
more than those plans? The learning proof's three placers on 96 more new plans per set (`models.datasets.fresh`, tag
"proof-wide"; `human` has none), 2 seeds, with the repairs. No decision rests on it.

    PYTHONPATH=. python app/bench/results/plan2place/repair-reward/proof_wide.py   # -> proof-wide.md
"""

import json
import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import mean_lines, paired_lines, runs  # noqa: E402

import run  # noqa: E402
from models.datasets.fresh import fresh_plans  # noqa: E402
from models.placement.base import get_solver  # noqa: E402
from models.placement.plan2place.solver import untrained_solver  # noqa: E402

METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2), ("key_nav", 100, True, 2),
           ("cnt", 100, True, 2))
run.SETS = ("seen", "unseen_a", "unseen_b", "dense")  # the sets fresh plans exist for
placers = [get_solver("plan2place"), get_solver("greedy"), untrained_solver()]
rows = runs(lambda ds: fresh_plans(ds, "proof-wide", 96), placers, METRICS)
(HERE / "proof-wide-rows.json").write_text(json.dumps(rows) + "\n")
names = [p.name for p in placers]
lines = ["The learning proof on 96 new plans per set x 2 seeds (proof_wide.py; metrics x 100 but energy), then the "
         "shipped weights minus each baseline, 95 % plan-bootstrap interval; bold: better, italic: worse, clear of 0",
         "", *mean_lines(rows, names, METRICS), "",
         *paired_lines(rows, [("plan2place", "greedy"), ("plan2place", "plan2place_untrained")], METRICS)]
(HERE / "proof-wide.md").write_text("\n".join(lines) + "\n")
print("\n".join(lines))
