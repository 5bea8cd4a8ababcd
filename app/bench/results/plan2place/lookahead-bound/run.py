"""How much could a critic that looks ahead give Plan2Place, once the repairs have run? An upper bound, by an
oracle that no network approximates yet: at each step it judges the K feasible candidates of lowest immediate
energy (those the reach guard keeps, if any) by placing each and finishing the episode greedily
(`agent.judge`, the training teacher's judgment), and takes the one of lowest final energy; then the same
repairs as greedy and Plan2Place. A diagnosis (not a solver: 60-220 ms per object), on the diagnosis plans off
the benchmark's sample (`i % step == step // 2`), 2 seeds, each placer with and without the repairs.

    PYTHONPATH=. python app/bench/results/plan2place/lookahead-bound/run.py [N_PLANS] [K]   # -> bound.md, rows.json
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from app.bench.gates import diagnosis_plans
from app.bench.paired import cell, interval, paired
from app.bench.placement import score
from models.placement.base import get_solver
from models.placement.greedy import Episode, GreedySolver
from models.placement.plan2place.solver import Plan2PlaceSolver
from models.placement.repair import repair

HERE = Path(__file__).parent
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2), ("key_nav", 100, True, 2),
           ("cnt", 100, True, 2))  # name, scale, higher is better, digits


def by_energy(ep, opts, rng) -> np.ndarray:
    """The feasible candidates by immediate energy (greedy's seeded tie-break)."""
    return np.argsort(opts.terms["total"] + rng.uniform(0, 1e-9, len(opts.feasible)), kind="stable")


class Oracle:
    """The look-ahead oracle of the module's docstring; `propose(ep, opts, rng)` orders the feasible candidates
    of which the first K are judged (default: by immediate energy)."""

    def __init__(self, k: int, repaired: bool, propose=by_energy, label: str = ""):
        self.k, self.repaired, self.propose = k, repaired, propose
        self.name = f"oracle K={k}{label}" + ("" if repaired else ", no repair")

    def solve(self, plan, seed: int = 0):
        start, rng = time.perf_counter(), np.random.default_rng(seed)
        ep = Episode(plan)
        while not ep.done:
            opts, pick = ep.options(), None
            if len(opts.feasible):
                order = self.propose(ep, opts, rng)[:self.k]
                kept = ep.keeping(opts, order)
                judged = order[kept] if kept.any() else order
                pick = int(judged[int(np.argmin(ep.judge(opts, judged)))])
            ep.apply(opts, pick)
        if self.repaired:
            repair(ep)
        return ep.layout(self.name, seed, time.perf_counter() - start)




def runs(plans_of, solvers, metrics=METRICS) -> list[dict]:
    """Every solver on the plans `plans_of(set)` of each set, seeds 0 and 1: one row per run with its `metrics`
    and its time per object (ms)."""
    rows = []
    for ds in SETS:
        for plan in plans_of(ds):
            for seed in (0, 1):
                for s in solvers:
                    t = time.perf_counter()
                    layout = s.solve(plan, seed=seed)
                    ms = 1000 * (time.perf_counter() - t) / len(plan.objects)
                    got = score(plan, layout)
                    rows.append({"set": ds, "plan": plan.id, "seed": seed, "solver": s.name, "ms": ms,
                                 **{m: got[m] for m, *_ in metrics}})
        print(ds, "done", flush=True)
    return rows


def mean_lines(rows: list[dict], names: list[str], metrics=METRICS) -> list[str]:
    """A table of each solver's means per set (scaled; a metric not applicable to a layout, such as realism, is
    left out of its mean) and its median time per object."""
    lines = ["| set | solver | " + " | ".join(m for m, *_ in metrics) + " | ms p50 |",
             "| --- | --- |" + " ---: |" * (len(metrics) + 1)]
    for ds in SETS:
        for name in names:
            mine = [r for r in rows if r["set"] == ds and r["solver"] == name]
            means = [sc * np.mean([r[m] for r in mine if r[m] is not None]) for m, sc, *_ in metrics]
            lines.append(f"| {ds} | {name} | " + " | ".join(f"{v:.{d}f}" for v, (*_, d) in zip(means, metrics)) +
                         f" | {np.median([r['ms'] for r in mine]):.1f} |")
    return lines


def paired_lines(rows: list[dict], pairs: list[tuple[str, str]], metrics=METRICS) -> list[str]:
    """A table of a - b per set for each (a, b) of `pairs`, with 95 % plan-bootstrap intervals."""
    rng = np.random.default_rng(0)
    lines = ["| set | pair | " + " | ".join(m for m, *_ in metrics) + " |", "| --- | --- |" + " --- |" * len(metrics)]
    for ds in SETS:
        mine = [r for r in rows if r["set"] == ds]
        for a, b in pairs:
            cells = [cell(*(sc * v for v in interval(paired(mine, m, a, b), rng)), up, d) for m, sc, up, d in metrics]
            lines.append(f"| {ds} | {a} - {b} | " + " | ".join(cells) + " |")
    return lines


def main(n: int, k: int) -> int:
    solvers = [GreedySolver(), get_solver("plan2place"), Oracle(k, True), GreedySolver(repair=False),
               Plan2PlaceSolver(repair=False, name="plan2place, no repair"), Oracle(k, False)]
    rows = runs(lambda ds: diagnosis_plans(ds, n), solvers)
    (HERE / "rows.json").write_text(json.dumps(rows) + "\n")
    names = [s.name for s in solvers]
    lines = [f"Look-ahead oracle (K = {k}) against greedy and Plan2Place, {n} diagnosis plans per set x 2 seeds "
             "(run.py); means, then the oracle minus each with a 95 % plan-bootstrap interval (bold: the oracle "
             "better, clear of 0); metrics x 100 but energy; ms per object, median", "", *mean_lines(rows, names), "",
             *paired_lines(rows, [(names[2], names[0]), (names[2], names[1]), (names[5], names[3]), (names[5], names[4])])]
    (HERE / "bound.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(int(sys.argv[1]) if len(sys.argv) > 1 else 16, int(sys.argv[2]) if len(sys.argv) > 2 else 4))
