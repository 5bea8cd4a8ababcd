"""`plan2place_exact` paired with `plan2place` and with Z3 over the same runs of `bench-human/` (the placement bench on
all 120 iTHOR rooms x 5 seeds with DFS, Z3 and both); writes `compare.md` here:

    PYTHONPATH=. python app/bench/results/plan2place/exact-finish/compare.py
"""
import json
import statistics
from pathlib import Path

import numpy as np

from app.bench.paired import cell, header, interval, paired

HERE = Path(__file__).parent
METRICS = (("cnt", 100, True, 2), ("key_nav", 100, True, 2), ("constraint_satisfaction", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3), ("pto", 1000, False, 2))

if __name__ == "__main__":
    rows = json.loads((HERE / "bench-human" / "results.json").read_text())
    rng = np.random.default_rng(0)
    lines = ["`plan2place_exact` minus another solver on `human` (120 rooms x 5 seeds, one bench run), mean over the "
             "same (plan, seed) runs [95 % bootstrap interval over plans]; metrics x 100, energy as is, PTO in ms per "
             "object; **bold** = `plan2place_exact` better with the interval clear of 0, _italic_ = worse.", "",
             *header("against", METRICS)]
    for other in ("plan2place", "z3", "dfs"):
        cells = [cell(*(scale * v for v in interval(paired(rows, m, "plan2place_exact", other), rng)), up, digits)
                 for m, scale, up, digits in METRICS]
        lines.append(f"| {other} | " + " | ".join(cells) + " |")
    changed = sum(1 for a in rows if a["solver"] == "plan2place_exact" for b in rows
                  if b["solver"] == "plan2place" and (a["plan"], a["seed"]) == (b["plan"], b["seed"])
                  and a["energy"] != b["energy"])
    solvers = ("dfs", "z3", "plan2place", "plan2place_exact")
    pto = {s: [1000 * r["pto"] for r in rows if r["solver"] == s] for s in solvers}
    lines += ["", f"Runs whose layout energy differs from `plan2place`'s: {changed} of {len(pto['plan2place'])}.", "",
              "PTO per object (ms): " + "; ".join(f"`{s}` p50 {statistics.median(v):.2f}, p90 "
                                                 f"{np.percentile(v, 90):.2f}, mean {statistics.mean(v):.2f}"
                                                 for s, v in pto.items())]
    (HERE / "compare.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
