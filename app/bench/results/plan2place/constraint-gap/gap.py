"""Where Plan2Place's constraint gap to the best other solver comes from, on the placement bench's stored runs.

For each set, the solver other than Plan2Place with the most constraints met (targets.best_other) is paired with it
run by run (same plan and seed). The mean difference in constraints met is split by what the other solver's layout
cost in each run where it met more: nothing (no worse than Plan2Place's in any of the guarded metrics: a layout
Plan2Place could have found and missed) or something (worse in one of them: a trade Plan2Place's repairs refuse by
rule, since a move may not raise the energy beyond the allowance nor leave task objects out of reach); runs where
Plan2Place met more are the third part. Two tables: guarded by energy and Key_NAV (what the repairs guard), and by
NAV as well (the share of free floor the robot reaches, which the energy's navigation term only approximates). Each part with a 95 % bootstrap interval over plans
(app.bench.paired). Reads app/bench/results/placement-*/results.json, writes gap.md beside this script:
python app/bench/results/plan2place/constraint-gap/gap.py"""

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from targets import RESULTS, SETS, best_other  # noqa: E402 (beside this directory)

from app.bench.paired import cell, interval  # noqa: E402

CS = "constraint_satisfaction"
GUARDS = ((("energy", False), ("key_nav", True)), (("energy", False), ("key_nav", True), ("nav", True)))
PARTS = ("missed", "traded", "ahead")


def part(p2p: dict, other: dict, guarded) -> str:
    """Which part of the gap one pair of runs belongs to (`PARTS`), or "" when both met as many; `guarded`:
    (metric, higher is better) pairs."""
    d = p2p[CS] - other[CS]
    if d >= 0:
        return "ahead" if d > 0 else ""
    worse = any(other[m] > p2p[m] + 1e-9 if not up else other[m] < p2p[m] - 1e-9 for m, up in guarded)
    return "traded" if worse else "missed"


def split(rows: list[dict], other: str, guarded) -> dict[str, dict[str, list[float]]]:
    """part -> plan -> the constraint differences of its runs in that part (0 for the plan's other runs)."""
    by = {(r["solver"], r["plan"], r["seed"]): r for r in rows}
    out = {p: {} for p in PARTS}
    for (solver, plan, seed), r in by.items():
        o = by.get((other, plan, seed))
        if solver != "plan2place" or o is None:
            continue
        k = part(r, o, guarded)
        for p in PARTS:
            out[p].setdefault(plan, []).append(r[CS] - o[CS] if p == k else 0.0)
    return out


def table(guarded, rng: np.random.Generator) -> list[str]:
    names = ", ".join(m for m, _ in guarded)
    lines = [f"Guarded: {names}.", "", "| set | vs | whole | missed | traded | ahead | runs missed / traded / ahead |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for s in SETS:
        rows = json.loads((RESULTS / f"placement-{s}" / "results.json").read_text())
        other = best_other(rows, CS, True)
        parts = split(rows, other, guarded)
        whole = {plan: list(np.sum([parts[p][plan] for p in PARTS], axis=0)) for plan in parts["ahead"]}
        counts = [sum(d != 0 for ds in parts[p].values() for d in ds) for p in PARTS]
        cells = [cell(*(100 * v for v in interval(d, rng)), True) for d in (whole, *(parts[p] for p in PARTS))]
        lines.append(f"| {s} | {other} | " + " | ".join(cells) + f" | {' / '.join(map(str, counts))} |")
    return lines


def main() -> str:
    rng = np.random.default_rng(0)
    lines = ["Plan2Place - the solver meeting the most constraints, constraints met x 100 over the same (plan, seed) "
             "pairs [95 % bootstrap interval over plans], split by run: **missed** = the other layout met more and was "
             "no worse in any guarded metric; **traded** = it met more but was worse in one of them; **ahead** = "
             "Plan2Place met more. The three parts sum to the whole."]
    for guarded in GUARDS:
        lines += ["", *table(guarded, rng)]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    text = main()
    (HERE / "gap.md").write_text(text)
    print(text)
