"""How many candidates should the look-ahead placer judge per step? The oracle of run.py with K = 2, 4 (the
shipped LOOKAHEAD_K) and 8, with the repairs, against Plan2Place, on the same diagnosis plans (not the bench's).
Rule, written before the run: K changes from 4 only if another K has a lower mean energy than K = 4 on at least 4
of the 5 sets at most 1.5 x its median time per object, or the same energy (within 0.005 on every set) for less time.

    PYTHONPATH=. python app/bench/results/plan2place/lookahead-bound/k.py [N_PLANS]   # -> k.md
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from models.placement.base import get_solver
from run import SETS, Oracle, diagnosis_plans, mean_lines, paired_lines, runs

HERE = Path(__file__).parent
KS = (2, 4, 8)


def main(n: int) -> int:
    solvers = [get_solver("plan2place"), *(Oracle(k, True) for k in KS)]
    rows = runs(lambda ds: diagnosis_plans(ds, n), solvers)
    names = [s.name for s in solvers]
    mean = {(ds, s): float(np.mean([r["energy"] for r in rows if r["set"] == ds and r["solver"] == s]))
            for ds in SETS for s in names}
    ms = {s: float(np.median([r["ms"] for r in rows if r["solver"] == s])) for s in names}
    four = names[2]
    verdict = []
    for other in (names[1], names[3]):
        lower = sum(mean[ds, other] < mean[ds, four] for ds in SETS)
        same = all(abs(mean[ds, other] - mean[ds, four]) <= 0.005 for ds in SETS)
        better = (lower >= 4 and ms[other] <= 1.5 * ms[four]) or (same and ms[other] < ms[four])
        verdict.append(f"{other}: lower energy than K = 4 on {lower} of {len(SETS)} sets, median {ms[other]:.1f} ms "
                       f"per object against {ms[four]:.1f}; replaces K = 4: {better}")
    lines = [f"The look-ahead oracle with K = {', '.join(map(str, KS))} against Plan2Place, {n} diagnosis plans per set x "
             "2 seeds (k.py), every placer with the repairs", "", *mean_lines(rows, names), "",
             *paired_lines(rows, [(o, names[0]) for o in names[1:]] + [(names[1], four), (names[3], four)]), "",
             *verdict]
    (HERE / "k.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(int(sys.argv[1]) if len(sys.argv) > 1 else 16))
