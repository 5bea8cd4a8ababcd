"""The hybrid of decision.md: Plan2Place, then, where its layout leaves a task object out of reach, the reach-kept
search (search.py) with a budget of B nodes, its layout taken iff it places at least as many objects and leaves
fewer task objects out of reach. Step 1 (choose B on the diagnosis plans) -> choose.md.

    PYTHONPATH=. python app/bench/results/plan2place/dense-feasible/hybrid.py   # -> choose.md, choose.json
"""

import json
import sys
import time
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import diagnosis_plans, mean_lines, paired_lines, runs  # noqa: E402
from search import search  # noqa: E402

from models.placement.base import get_solver  # noqa: E402
from models.placement.candidates import CandidateScorer  # noqa: E402
from models.placement.problem import PlacementProblem  # noqa: E402
from models.placement.reach import Reach  # noqa: E402

BUDGETS = (25, 50, 100, 200)
METRICS = (("energy", 1, False, 3), ("key_nav", 100, True, 2), ("cnt", 100, True, 2),
           ("constraint_satisfaction", 100, True, 2), ("realism", 100, True, 2))


def reach_of(plan, layout) -> tuple[set, int, int]:
    """(ids placed, placed task objects out of reach, task objects not reached: out of reach or not placed)."""
    problem = PlacementProblem.from_plan(plan)
    scorer, reach = CandidateScorer(problem), Reach(problem)
    placed = [scorer.place(plan.object(p.id), p.x, p.z, p.rotation) for p in layout.placements]
    walled = len(reach.unreachable(placed))
    return {p.id for p in placed}, walled, len(reach.task) - (len([p for p in placed if p.id in reach.task]) - walled)


class Hybrid:
    def __init__(self, nodes: int):
        self.nodes, self.name, self.p2p = nodes, f"hybrid B={nodes}", get_solver("plan2place")
        self.taken = 0

    def solve(self, plan, seed: int = 0):
        layout = self.p2p.solve(plan, seed=seed)
        n, walled, out = reach_of(plan, layout)
        if walled == 0:
            return layout
        alt = search(plan, seed, budget=60.0, max_nodes=self.nodes)[0]
        n_alt, _, out_alt = reach_of(plan, alt)
        if n_alt >= n and out_alt < out:  # n_alt >= n: it places every object Plan2Place placed
            self.taken += 1
            return alt
        return layout


def main() -> None:
    solvers = [get_solver("plan2place"), *(Hybrid(b) for b in BUDGETS)]
    t = time.perf_counter()
    rows = runs(lambda ds: diagnosis_plans(ds, 20), solvers, METRICS)
    (HERE / "choose.json").write_text(json.dumps(rows) + "\n")
    names = [s.name for s in solvers]
    lines = ["Step 1 of decision.md: the hybrid with B nodes against Plan2Place, diagnosis plans 20 per set x 2 seeds "
             f"(hybrid.py; {time.perf_counter() - t:.0f} s); means (metrics x 100 but energy; ms per object, median), "
             "then each hybrid minus Plan2Place with a 95 % plan-bootstrap interval", "",
             "layouts taken from the search: " + ", ".join(f"B={s.nodes}: {s.taken}" for s in solvers[1:]), "",
             *mean_lines(rows, names, METRICS), "", *paired_lines(rows, [(n, "plan2place") for n in names[1:]], METRICS)]
    (HERE / "choose.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
