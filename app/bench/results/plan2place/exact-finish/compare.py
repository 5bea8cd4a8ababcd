"""`plan2place_exact` paired with `plan2place`, Z3 and DFS over the same runs of each `bench-<set>/` here (the
placement bench with those four solvers, one run per set: `human` all 120 iTHOR rooms x 5 seeds, `seen` and `unseen_a`
100 plans x 5 seeds, Z3's rows run again with `--update` once each solve had a Z3 context of its own; `unseen_b` and
`dense` 100 plans x 5 seeds, their DFS and Z3 rows those of the placement bench's `placement-<set>/`, the two
Plan2Place solvers run together with `--update`); writes `compare.md` here:

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
SOLVERS = ("dfs", "z3", "plan2place", "plan2place_exact")


def report(name: str, rows: list[dict]) -> list[str]:
    rng = np.random.default_rng(0)
    lines = [f"`plan2place_exact` minus another solver on `{name}` (one bench run), mean over the same (plan, seed) "
             "runs [95 % bootstrap interval over plans]; metrics x 100, energy as is, PTO in ms per object; **bold** "
             "= `plan2place_exact` better with the interval clear of 0, _italic_ = worse.", "",
             *header("against", METRICS)]
    for other in ("plan2place", "z3", "dfs"):
        cells = [cell(*(scale * v for v in interval(paired(rows, m, "plan2place_exact", other), rng)), up, digits)
                 for m, scale, up, digits in METRICS]
        lines.append(f"| {other} | " + " | ".join(cells) + " |")
    energy = {(r["plan"], r["seed"]): r["energy"] for r in rows if r["solver"] == "plan2place"}
    exact = [r for r in rows if r["solver"] == "plan2place_exact"]
    changed = sum(r["energy"] != energy[(r["plan"], r["seed"])] for r in exact)
    pto = {s: [1000 * r["pto"] for r in rows if r["solver"] == s] for s in SOLVERS}
    return lines + ["", f"Runs whose layout energy differs from `plan2place`'s: {changed} of {len(exact)}.", "",
                    "PTO per object (ms): " + "; ".join(f"`{s}` p50 {statistics.median(v):.2f}, p90 "
                                                       f"{np.percentile(v, 90):.2f}, mean {statistics.mean(v):.2f}"
                                                       for s, v in pto.items())]


if __name__ == "__main__":
    parts = [report(d.name.removeprefix("bench-"), json.loads((d / "results.json").read_text()))
             for d in sorted(HERE.glob("bench-*"))]
    text = "\n\n".join("\n".join(p) for p in parts) + "\n"
    (HERE / "compare.md").write_text(text)
    print(text)
