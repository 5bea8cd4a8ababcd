"""A diagnosis, not a change: what if Plan2Place left an object out wherever the reach guard gives up (every candidate
it tries walls a task object off), instead of placing the most wanted? Key_NAV and CNT on the diagnosis plans (16 per
set, 2 seeds), the repairs as usual.

    PYTHONPATH=. python app/bench/results/plan2place/reach-first/try.py   # -> try.md
"""

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import SETS, diagnosis_plans, mean_lines, paired_lines, runs  # noqa: E402

from models.placement.base import get_solver  # noqa: E402
from models.placement.greedy import GUARD_TRIES, place_stepwise  # noqa: E402
from models.placement.plan2place.features import choose_subset, observe  # noqa: E402
from models.placement.plan2place.policy import shipped_policy, shipped_weights  # noqa: E402

METRICS = (("energy", 1, False, 3), ("key_nav", 100, True, 2), ("cnt", 100, True, 2),
           ("constraint_satisfaction", 100, True, 2), ("realism", 100, True, 2))


class ReachFirst:
    name = "reach-first"

    def solve(self, plan, seed=0):
        policy, use_global = shipped_policy(), shipped_weights().use_global

        def choose(ep, opts, rng):
            if opts.obj.id in ep.problem.fixed:
                return 0, np.ones(1), ""
            subset = choose_subset(opts, rng)
            logits = policy(observe(ep, opts, subset, use_global))
            order = subset[np.argsort(-logits, kind="stable")]
            keeps = ep.keeping(opts, order[:GUARD_TRIES])
            probs = np.zeros(len(opts.feasible))
            if not keeps.any():
                return None, probs, "left out: every pose tried walls off a task object"
            probs[order[int(np.argmax(keeps))]] = 1.0
            return int(order[int(np.argmax(keeps))]), probs, ""

        return place_stepwise(plan, np.random.default_rng(seed), choose).layout(self.name, seed, 0.0)


placers = [get_solver("plan2place"), ReachFirst()]
rows = runs(lambda ds: diagnosis_plans(ds, 16), placers, METRICS)
names = [p.name for p in placers]
lines = [*mean_lines(rows, names, METRICS), "", *paired_lines(rows, [("reach-first", "plan2place")], METRICS)]
(HERE / "try.md").write_text("Reach first (leave the object out where the guard gives up) against Plan2Place, "
                             "diagnosis plans 16 per set x 2 seeds (try.py)\n\n" + "\n".join(lines) + "\n")
print("\n".join(lines))
