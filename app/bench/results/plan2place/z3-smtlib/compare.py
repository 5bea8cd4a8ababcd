"""The placement bench's rows before and after Z3 read its model as SMT-LIB text and the exact finish's budget became
Z3's resource count (5a8166f): Z3 the baseline, and the step-wise placers whose last repair is the finish. Paired over
the same (plan, seed) runs, 95 % bootstrap interval over plans (app.bench.paired). The rows before are read from git at
BEFORE; writes compare.md beside this script:

    PYTHONPATH=. python app/bench/results/plan2place/z3-smtlib/compare.py
"""
import json
import statistics
import subprocess
from pathlib import Path

import numpy as np

from app.bench.paired import cell, header, interval, paired

HERE = Path(__file__).parent
RESULTS = HERE.parents[1]
BEFORE = "993808a"
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
SOLVERS = ("z3", "plan2place", "greedy", "lookahead")
METRICS = (("cnt", 100, True, 2), ("key_nav", 100, True, 2), ("constraint_satisfaction", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3))
SAME = ("cnt", "key_nav", "constraint_satisfaction", "realism", "energy", "oob")


def rows(name: str, solver: str, commit: str | None) -> list[dict]:
    """`solver`'s rows of set `name`, from git at `commit` (None: the working tree)."""
    path = f"app/bench/results/placement-{name}/results.json"
    text = (RESULTS.parent.parent.parent / path).read_text() if commit is None else subprocess.run(
        ["git", "show", f"{commit}:{path}"], capture_output=True, text=True, check=True, cwd=HERE).stdout
    return [r for r in json.loads(text) if r["solver"] == solver]


def changed(old: list[dict], new: list[dict]) -> int:
    """Runs whose judged figures differ (the rows hold no poses)."""
    before = {(r["plan"], r["seed"]): r for r in old}
    return sum(any(abs((r[k] or 0) - (before[(r["plan"], r["seed"])][k] or 0)) > 1e-9 for k in SAME)
               for r in new if (r["plan"], r["seed"]) in before)


def main() -> str:
    rng = np.random.default_rng(0)
    lines = ["After minus before (Z3 reading SMT-LIB text; the exact finish on a work budget), the same (plan, seed) "
             "runs of the placement bench, mean [95 % bootstrap interval over plans]; metrics x 100, energy as is; "
             "**bold** = after better with the interval clear of 0, _italic_ = worse. Last columns: runs whose judged "
             "figures changed, and PTO p50 and mean (ms per object), before -> after.", ""]
    for solver in SOLVERS:
        lines += [f"**{solver}**", "", header("set", METRICS)[0] + " changed | PTO p50 | PTO mean |",
                  header("set", METRICS)[1] + " --- | --- | --- |"]
        for name in SETS:
            new, old = rows(name, solver, None), rows(name, solver, BEFORE)
            if not new or not old:
                continue
            both = new + [{**r, "solver": "before"} for r in old]
            cells = [cell(*(scale * v for v in interval(paired(both, m, solver, "before"), rng)), up, digits)
                     for m, scale, up, digits in METRICS]
            p50 = [1000 * statistics.median(r["pto"] for r in rs) for rs in (old, new)]
            mean = [1000 * statistics.fmean(r["pto"] for r in rs) for rs in (old, new)]
            lines.append(f"| {name} | " + " | ".join(cells) + f" | {changed(old, new)} of {len(new)} | "
                         f"{p50[0]:.1f} -> {p50[1]:.1f} | {mean[0]:.1f} -> {mean[1]:.1f} |")
        lines.append("")
    return "\n".join(lines)


if __name__ == "__main__":
    text = main()
    (HERE / "compare.md").write_text(text)
    print(text)
