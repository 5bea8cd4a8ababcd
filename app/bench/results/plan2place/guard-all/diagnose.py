"""How often the reach guard gives up on `dense` (none of its first GUARD_TRIES candidates keeps every task object
in reach, so the most wanted walls one off), and whether a candidate further down the feasible list would have kept
reach. Plan2Place and greedy on the diagnosis plans (16 per set, 2 seeds); no fitting, nothing changed.

    PYTHONPATH=. python app/bench/results/plan2place/guard-all/diagnose.py   # -> diagnose.md
"""

import sys
from collections import Counter
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

from models.placement.base import get_solver  # noqa: E402
from models.placement.greedy import GUARD_TRIES, Episode  # noqa: E402

counts: Counter = Counter()
original = Episode.first_kept


def watched(self, opts, order, k):
    kept = original(self, opts, order, k)
    if k == 1:
        counts["steps guarded"] += 1
        tried = order[:GUARD_TRIES]
        if not self.keeping(opts, tried[:1]).any() and not self.keeping(opts, tried).any():
            counts["gave up (none of the tried keeps reach)"] += 1
            rest = np.setdiff1d(np.arange(len(opts.feasible)), tried)
            counts["... and a feasible candidate not tried keeps reach"] += bool(len(rest) and self.keeping(opts, rest).any())
    return kept


Episode.first_kept = watched
lines = ["| set | solver | steps guarded | gave up | of those, another feasible candidate keeps reach |",
         "| --- | --- | ---: | ---: | ---: |"]
for ds in ("dense", "unseen_a", "seen"):
    for name in ("plan2place", "greedy"):
        counts.clear()
        solver = get_solver(name)
        for plan in diagnosis_plans(ds, 16):
            for seed in (0, 1):
                solver.solve(plan, seed=seed)
        lines.append(f"| {ds} | {name} | {counts['steps guarded']} | {counts['gave up (none of the tried keeps reach)']} "
                     f"| {counts['... and a feasible candidate not tried keeps reach']} |")
        print(lines[-1], flush=True)
(HERE / "diagnose.md").write_text("The reach guard on the diagnosis plans (16 per set x 2 seeds; diagnose.py)\n\n"
                                  + "\n".join(lines) + "\n")
