"""Does the learned policy propose better candidates for a look-ahead than the immediate energy does? The oracle
of run.py judging the K first candidates of three orders: immediate energy, the shipped policy's logits and the
untrained network's (each over its step's candidate subset, `choose_subset`), every placer with the repairs, on
the same diagnosis plans.

    PYTHONPATH=. python app/bench/results/plan2place/lookahead-bound/proposals.py [N_PLANS] [K]   # -> proposals.md
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from app.bench.paired import cell, interval, paired
from app.bench.placement import score
from models.placement.plan2place.agent import fast_policy, untrained_network
from models.placement.plan2place.features import choose_subset, observe
from models.placement.plan2place.policy import shipped_policy
from run import METRICS, SETS, Oracle, diagnosis_plans

HERE = Path(__file__).parent


def by_policy(policy):
    def propose(ep, opts, rng) -> np.ndarray:
        subset = choose_subset(opts, rng)
        return subset[np.argsort(-policy(observe(ep, opts, subset)), kind="stable")]
    return propose


def main(n: int, k: int) -> int:
    oracles = [Oracle(k, True), Oracle(k, True, by_policy(shipped_policy()), ", policy's"),
               Oracle(k, True, by_policy(fast_policy(untrained_network())), ", untrained network's")]
    rows = []
    for ds in SETS:
        for plan in diagnosis_plans(ds, n):
            for seed in (0, 1):
                for o in oracles:
                    t = time.perf_counter()
                    layout = o.solve(plan, seed=seed)
                    got = score(plan, layout)
                    rows.append({"set": ds, "plan": plan.id, "seed": seed, "solver": o.name,
                                 "ms": 1000 * (time.perf_counter() - t) / len(plan.objects),
                                 **{m: got[m] for m, _ in METRICS}})
        print(ds, "done", flush=True)
    rng = np.random.default_rng(0)
    names = [o.name for o in oracles]
    lines = [f"The look-ahead oracle (K = {k}, with the repairs) judging the first K candidates of three orders, "
             f"{n} diagnosis plans per set x 2 seeds (proposals.py); means (metrics x 100 but energy), then the "
             "policy's proposals minus the others', 95 % plan-bootstrap interval (bold: the policy's better)", "",
             "| set | proposals | " + " | ".join(m for m, _ in METRICS) + " | ms p50 |",
             "| --- | --- |" + " ---: |" * (len(METRICS) + 1)]
    for ds in SETS:
        for name in names:
            mine = [r for r in rows if r["set"] == ds and r["solver"] == name]
            lines.append(f"| {ds} | {name} | " + " | ".join(
                f"{np.mean([r[m] for r in mine]) * (1 if m == 'energy' else 100):.{3 if m == 'energy' else 2}f}"
                for m, _ in METRICS) + f" | {np.median([r['ms'] for r in mine]):.1f} |")
    lines += ["", "| set | policy's minus | " + " | ".join(m for m, _ in METRICS) + " |",
              "| --- | --- |" + " --- |" * len(METRICS)]
    for ds in SETS:
        mine = [r for r in rows if r["set"] == ds]
        for other in (names[0], names[2]):
            cells = []
            for m, higher in METRICS:
                scale = 1 if m == "energy" else 100
                diffs = {p: [scale * d for d in v] for p, v in paired(mine, m, names[1], other).items()}
                cells.append(cell(*interval(diffs, rng), higher, digits=3 if m == "energy" else 2))
            lines.append(f"| {ds} | {other} | " + " | ".join(cells) + " |")
    (HERE / "proposals.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(int(sys.argv[1]) if len(sys.argv) > 1 else 16, int(sys.argv[2]) if len(sys.argv) > 2 else 4))
