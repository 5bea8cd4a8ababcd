"""What solving once more where the layout is a few constraints short of all would add, estimated from the placement
bench's stored runs as `constraint-gap/second-opinion.py` does (nothing solved again): where Plan2Place's layout leaves
1 (or at most 2) constraints unmet, its layout at the next seed replaces it by the second solve's rule, and the run's
time is counted twice. Writes estimate.md:
PYTHONPATH=. python app/bench/results/plan2place/one-short/estimate.py"""

import importlib
import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE.parent), str(HERE.parent / "constraint-gap")]
from targets import RESULTS, SETS, best_other  # noqa: E402 (beside this directory)

from app.bench.paired import cell, interval, paired  # noqa: E402
from app.bench.placement import pick_records  # noqa: E402
from models.placement.problem import PlacementProblem  # noqa: E402

CS = "constraint_satisfaction"
kept = importlib.import_module("second-opinion").kept


def totals(dataset: str, n: int) -> dict[str, int]:
    """Each bench plan's constraints, as the metric counts them (a global and the relations per object)."""
    return {r.plan.id: sum(1 + len(oc.relations) for oc in PlacementProblem.from_plan(r.plan).constraints.objects.values())
            for r in pick_records(dataset, n)}


def main() -> str:
    rng = np.random.default_rng(0)
    lines = [__doc__.split("\n\n")[0].replace("\n", " "), "",
             "| set | fires where unmet | fired | kept | constraints, with - without | gap to the best other: now -> with "
             "| PTO p50 (ms), now -> with (estimate) |", "| --- | --- | --- | --- | --- | --- | --- |"]
    for s in SETS:
        rows = json.loads((RESULTS / f"placement-{s}" / "results.json").read_text())
        total = totals(s, len({r["plan"] for r in rows}))
        by = {(r["solver"], r["plan"], r["seed"]): r for r in rows}
        seeds = sorted({r["seed"] for r in rows})
        best = best_other(rows, CS, True)
        p2p = [r for r in rows if r["solver"] == "plan2place"]
        for limit in (1, 2):
            out, fired, taken = [], 0, 0
            for r in p2p:
                fire = 0 < round((1 - r[CS]) * total[r["plan"]]) <= limit
                other = by[("plan2place", r["plan"], seeds[(seeds.index(r["seed"]) + 1) % len(seeds)])]
                use = other if fire and kept(r, other) else r
                fired, taken = fired + fire, taken + (use is other)
                out.append({**use, "solver": "with", "plan": r["plan"], "seed": r["seed"],
                            "pto": r["pto"] * (2 if fire else 1)})
            both = rows + out
            gain = cell(*(100 * v for v in interval(paired(both, CS, "with", "plan2place"), rng)), True)
            gaps = [cell(*(100 * v for v in interval(paired(both, CS, a, best), rng)), True) for a in ("plan2place", "with")]
            p50 = [1000 * np.median([r["pto"] for r in rs]) for rs in (p2p, out)]
            lines.append(f"| {s} | 1-{limit} | {fired} of {len(p2p)} | {taken} | {gain} | {gaps[0]} -> {gaps[1]} vs {best} "
                         f"| {p50[0]:.1f} -> {p50[1]:.1f} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    (HERE / "estimate.md").write_text(text := main())
    print(text)
