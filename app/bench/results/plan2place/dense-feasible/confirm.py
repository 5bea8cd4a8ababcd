"""Step 2 of decision.md: the hybrid (B = 50, round 2) against Plan2Place on plans no one has placed:
`fresh_plans(set, "reach-dfs")`, 24 per set (`human`: its diagnosis plans, having no fresh ones), seeds 0 and 1.

    PYTHONPATH=. python app/bench/results/plan2place/dense-feasible/confirm.py   # -> confirm.md, confirm.json
"""

import json
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from hybrid import METRICS, Hybrid  # noqa: E402
from run import diagnosis_plans, mean_lines, paired_lines, runs  # noqa: E402

from models.datasets.fresh import fresh_plans  # noqa: E402
from models.placement.base import get_solver  # noqa: E402

B, TAG, N = 50, "reach-dfs", 24


def plans_of(ds: str) -> list:
    return diagnosis_plans(ds, 20) if ds == "human" else fresh_plans(ds, TAG, N)


def main() -> None:
    hybrid = Hybrid(B)
    t = time.perf_counter()
    rows = runs(plans_of, [get_solver("plan2place"), hybrid], METRICS)
    (HERE / "confirm.json").write_text(json.dumps(rows) + "\n")
    dense = [r["ms"] for r in rows if r["set"] == "dense" and r["solver"] == hybrid.name]
    lines = [f"Step 2 of decision.md: {hybrid.name} against Plan2Place on {N} fresh plans per set (tag {TAG!r}; "
             f"`human`: 20 diagnosis plans) x 2 seeds (confirm.py; {time.perf_counter() - t:.0f} s); layouts taken "
             f"from the search: {hybrid.taken}; `dense` ms per object of the hybrid: mean {np.mean(dense):.1f}, "
             f"p90 {np.percentile(dense, 90):.1f}", "",
             *mean_lines(rows, ["plan2place", hybrid.name], METRICS), "",
             *paired_lines(rows, [(hybrid.name, "plan2place")], METRICS)]
    (HERE / "confirm.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
