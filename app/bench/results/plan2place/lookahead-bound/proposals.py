"""Does the learned policy propose better candidates for a look-ahead than the immediate energy does? The oracle
of run.py judging the K first candidates of three orders: immediate energy, the shipped policy's logits and the
untrained network's (each over its step's candidate subset, `choose_subset`), every placer with the repairs, on
the same diagnosis plans.

    PYTHONPATH=. python app/bench/results/plan2place/lookahead-bound/proposals.py [N_PLANS] [K]   # -> proposals.md
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from models.placement.plan2place.agent import fast_policy, untrained_network
from models.placement.plan2place.features import choose_subset, observe
from models.placement.plan2place.policy import shipped_policy
from run import Oracle, diagnosis_plans, mean_lines, paired_lines, runs

HERE = Path(__file__).parent


def by_policy(policy):
    def propose(ep, opts, rng) -> np.ndarray:
        subset = choose_subset(opts, rng)
        return subset[np.argsort(-policy(observe(ep, opts, subset)), kind="stable")]
    return propose


def main(n: int, k: int) -> int:
    oracles = [Oracle(k, True), Oracle(k, True, by_policy(shipped_policy()), ", policy's"),
               Oracle(k, True, by_policy(fast_policy(untrained_network())), ", untrained network's")]
    rows = runs(lambda ds: diagnosis_plans(ds, n), oracles)
    names = [o.name for o in oracles]
    lines = [f"The look-ahead oracle (K = {k}, with the repairs) judging the first K candidates of three orders, "
             f"{n} diagnosis plans per set x 2 seeds (proposals.py); means (metrics x 100 but energy), then the "
             "policy's proposals minus the others', 95 % plan-bootstrap interval (bold: the policy's better)", "",
             *mean_lines(rows, names), "", *paired_lines(rows, [(names[1], names[0]), (names[1], names[2])])]
    (HERE / "proposals.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(int(sys.argv[1]) if len(sys.argv) > 1 else 16, int(sys.argv[2]) if len(sys.argv) > 2 else 4))
