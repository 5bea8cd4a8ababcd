"""Front strips blocked: in how many places a solver's layout puts an object in another's front clearance (the
strip a fridge door, a drawer or a seat needs; tied pairs such as a chair at its table excepted), beside the
constraints it meets. MILP and Z3 treat that clearance as soft (a penalty); DFS, greedy and Plan2Place as a hard
filter relaxed only for an object with no other legal pose. This shows what each way costs and buys. 16 plans per set off the benchmarks' samples (`i % step == step // 2`), 2 seeds. Run from the root:
python app/bench/results/plan2place/blocked-fronts.py dense,seen dfs,milp,z3,greedy,plan2place | grep '^|' > blocked-fronts.md"""

import sys

import numpy as np

from models.datasets import load_dataset
from models.geometry import boxes, overlap_many
from models.metrics.placement import scene_metrics
from models.placement.base import get_solver
from models.placement.candidates import OVERLAP_TOL, front_boxes
from models.placement.problem import PlacementProblem


def blocked_strips(plan, layout) -> int:
    """(object, other object) pairs where the other's body stands in the object's front clearance strip."""
    problem = PlacementProblem.from_plan(plan)
    placed = {p.id: p for p in layout.placements}
    count = 0
    for a, pa in placed.items():
        depth = problem.clearance.get(a, 0.0)
        if depth <= 0:
            continue
        strip = front_boxes(pa.x, pa.z, pa.rotation, pa.size.x, pa.size.z, depth)[None]
        others = [boxes(p.x, p.z, p.size.x, p.size.z, p.rotation) for o, p in placed.items()
                  if o != a and not problem.constraints.tied(a, o)]
        if others:
            count += int((overlap_many(strip, np.stack(others))[0] > OVERLAP_TOL).sum())
    return count


def main(sets: list[str], solvers: list[str]) -> str:
    lines = ["| set | solver | blocked strips per scene | scenes with one (%) | constraints | Key_NAV |",
             "| --- | --- | --- | --- | --- | --- |"]
    for ds in sets:
        records = load_dataset(ds, "validation" if ds == "seen" else None)
        step = max(len(records) // 20, 1)
        plans = [r.plan for i, r in enumerate(records) if i % step == step // 2][:16]
        for name in solvers:
            solver, blocked, met, reach = get_solver(name), [], [], []
            for plan in plans:
                for seed in (0, 1):
                    layout = solver.solve(plan, seed=seed)
                    m = scene_metrics(plan, layout)
                    blocked.append(blocked_strips(plan, layout))
                    met.append(m.constraint_satisfaction)
                    reach += [m.key_nav] if m.key_nav is not None else []
            lines.append(f"| {ds} | {name} | {np.mean(blocked):.2f} | {100 * np.mean(np.array(blocked) > 0):.0f} | "
                         f"{100 * np.mean(met):.2f} | {100 * np.mean(reach):.2f} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    print(main(sys.argv[1].split(","), sys.argv[2].split(",")))
