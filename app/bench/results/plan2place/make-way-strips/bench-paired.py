"""The placement bench's own runs before (cb684c1) and after the make-way change, paired: Plan2Place and greedy,
new - old over the same (plan, seed) pairs (20 plans x 5 seeds per set), 95 % bootstrap intervals over plans.
Both from the stored results.json (the old one from git). From the root:
python app/bench/results/plan2place/make-way-strips/bench-paired.py > app/bench/results/plan2place/make-way-strips/bench-paired.md
A later change passes its own "before" commit: `bench-paired.py ddc8c37 > ../exact-baseline/bench-paired.md` (the
exact baseline and the compiled kernels); PTO is then paired too (two runs, each with two workers sharing the
CPU, on different days: a rough figure, the speed bench is the measure)."""
import json
import subprocess
import sys

import numpy as np

from app.bench.paired import cell, header, interval, paired

BEFORE = sys.argv[1] if len(sys.argv) > 1 else "cb684c1"
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
METRICS = (("constraint_satisfaction", 100, True, 2), ("key_nav", 100, True, 2), ("cnt", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3)) + ((("pto", 1000, False, 2),) if len(sys.argv) > 1 else ())


def rows(ds: str, version: str | None) -> list[dict]:
    path = f"app/bench/results/placement-{ds}/results.json"
    text = subprocess.check_output(["git", "show", f"{version}:{path}"]) if version else open(path).read()
    return json.loads(text)


def main() -> str:
    rng, lines = np.random.default_rng(0), header("set / solver: after - before", METRICS)
    for ds in SETS:
        old, new = rows(ds, BEFORE), rows(ds, None)
        for name in ("plan2place", "greedy"):
            both = [{**r, "solver": "before"} for r in old if r["solver"] == name] + \
                   [{**r, "solver": "after"} for r in new if r["solver"] == name]
            cells = [cell(*(sc * v for v in interval(paired(both, m, "after", "before"), rng)), up, d)
                     for m, sc, up, d in METRICS]
            lines.append(f"| {ds} / {name} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    print(main())
