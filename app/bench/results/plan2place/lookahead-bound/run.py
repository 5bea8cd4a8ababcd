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

from app.bench.paired import cell, interval, paired
from app.bench.placement import score
from models.datasets import load_dataset
from models.placement.base import get_solver
from models.placement.greedy import Episode, GreedySolver
from models.placement.plan2place.solver import Plan2PlaceSolver
from models.placement.repair import repair

HERE = Path(__file__).parent
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
METRICS = (("energy", False), ("constraint_satisfaction", True), ("key_nav", True), ("cnt", True))


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


def diagnosis_plans(ds: str, n: int) -> list:
    recs = load_dataset(ds, "validation" if ds == "seen" else None)
    step = max(len(recs) // 20, 1)
    return [r.plan for i, r in enumerate(recs) if i % step == step // 2][:n]


def main(n: int, k: int) -> int:
    solvers = [GreedySolver(), get_solver("plan2place"), Oracle(k, True), GreedySolver(repair=False),
               Plan2PlaceSolver(repair=False, name="plan2place, no repair"), Oracle(k, False)]
    rows = []
    for ds in SETS:
        for plan in diagnosis_plans(ds, n):
            for seed in (0, 1):
                for s in solvers:
                    t = time.perf_counter()
                    layout = s.solve(plan, seed=seed)
                    ms = 1000 * (time.perf_counter() - t) / len(plan.objects)
                    scored = score(plan, layout)
                    rows.append({"set": ds, "plan": plan.id, "seed": seed, "solver": s.name, "ms": ms,
                                 **{m: scored[m] for m, _ in METRICS}})
        print(ds, "done", flush=True)
    (HERE / "rows.json").write_text(json.dumps(rows) + "\n")
    rng = np.random.default_rng(0)
    lines = [f"Look-ahead oracle (K = {k}) against greedy and Plan2Place, {n} diagnosis plans per set x 2 seeds "
             "(run.py); means, then the oracle minus each with a 95 % plan-bootstrap interval (bold: the oracle "
             "better, clear of 0); metrics x 100 but energy; ms per object, median", ""]
    names = [s.name for s in solvers]
    lines += ["| set | solver | " + " | ".join(m for m, _ in METRICS) + " | ms |", "| --- | --- |" + " ---: |" * 5]
    for ds in SETS:
        for name in names:
            mine = [r for r in rows if r["set"] == ds and r["solver"] == name]
            scale = {m: 1 if m == "energy" else 100 for m, _ in METRICS}
            lines.append(f"| {ds} | {name} | " + " | ".join(
                f"{scale[m] * np.mean([r[m] for r in mine]):.3f}" if m == "energy" else
                f"{scale[m] * np.mean([r[m] for r in mine]):.2f}" for m, _ in METRICS) +
                f" | {np.median([r['ms'] for r in mine]):.1f} |")
    lines += ["", "| set | oracle minus | " + " | ".join(m for m, _ in METRICS) + " |", "| --- | --- |" + " --- |" * 4]
    for ds in SETS:
        mine = [r for r in rows if r["set"] == ds]
        for a, b in ((names[2], names[0]), (names[2], names[1]), (names[5], names[3]), (names[5], names[4])):
            cells = []
            for m, higher in METRICS:
                scale = 1 if m == "energy" else 100
                diffs = {p: [scale * d for d in v] for p, v in paired(mine, m, a, b).items()}
                cells.append(cell(*interval(diffs, rng), higher, digits=3 if m == "energy" else 2))
            lines.append(f"| {ds} | {b} | " + " | ".join(cells) + " |")
    (HERE / "bound.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(int(sys.argv[1]) if len(sys.argv) > 1 else 16, int(sys.argv[2]) if len(sys.argv) > 2 else 4))
