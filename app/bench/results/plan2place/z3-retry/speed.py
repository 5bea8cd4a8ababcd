"""Whether the placement bench's slower times after the retries are the placers' or the machine's: for each set rerun,
the PTO p50 of each solver over the runs whose layout is the same in both runs (same energy and constraints met), in
the run before the retries (the stored results at `BEFORE`) and after. Writes speed.txt beside it:
PYTHONPATH=. python app/bench/results/plan2place/z3-retry/speed.py"""

import json
import statistics
import subprocess
from pathlib import Path

HERE, RESULTS = Path(__file__).parent, Path(__file__).parents[2]
BEFORE = "06557f1"  # the commit whose stored runs are the bench's before the retries
SETS, SOLVERS = ("seen", "unseen_a", "human"), ("dfs", "greedy", "plan2place", "lookahead")


def key(r: dict) -> tuple:
    return r["solver"], r["plan"], r["seed"]


lines = [f"PTO p50 (ms per object) over the runs whose layout is unchanged, the run at {BEFORE} -> now"]
for s in SETS:
    path = RESULTS / f"placement-{s}" / "results.json"
    old = {key(r): r for r in json.loads(subprocess.check_output(
        ["git", "show", f"{BEFORE}:{path.relative_to(RESULTS.parents[2])}"], cwd=RESULTS))}
    for solver in SOLVERS:
        same = [(old[key(r)]["pto"], r["pto"]) for r in json.loads(path.read_text()) if r["solver"] == solver
                and old[key(r)]["energy"] == r["energy"]
                and old[key(r)]["constraint_satisfaction"] == r["constraint_satisfaction"]]
        a, b = (1000 * statistics.median(x[i] for x in same) for i in (0, 1))
        lines.append(f"{s} / {solver}: {len(same)} runs, {a:.2f} -> {b:.2f} ({b / a:.2f} x)")
(HERE / "speed.txt").write_text("\n".join(lines) + "\n")
print("\n".join(lines))
