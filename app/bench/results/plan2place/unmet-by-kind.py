"""Which constraints each solver leaves unmet, by kind (a global placement `edge` / `middle`, or a relation's
name; "absent" when one of its objects was left out), per scene: where Plan2Place's constraints gap to the best
baseline comes from. 16 plans per set off the benchmarks' samples (`i % step == step // 2`), 2 seeds. Run from
the root: python app/bench/results/plan2place/unmet-by-kind.py seen,dense z3,milp,dfs,plan2place > unmet-by-kind.md"""

import sys
from collections import Counter

import numpy as np

from models.constraints.evaluate import Poses, placement, relation, wall_clearance
from models.datasets import load_dataset
from models.placement.base import get_solver
from models.placement.problem import PlacementProblem


def unmet(plan, layout) -> Counter:
    """Unmet constraints of `layout` by kind, counted as the constraints metric counts them."""
    problem, room = PlacementProblem.from_plan(plan), plan.room
    at = {p.id: Poses.one(p.x, p.z, p.rotation, p.size.x, p.size.z) for p in layout.placements}
    out: Counter = Counter()
    for oid, oc in problem.constraints.objects.items():
        a = at.get(oid)
        if a is None:
            out["absent"] += 1 + len(oc.relations)
            continue
        clearance = wall_clearance(a, room.width, room.depth)
        out[oc.placement] += not placement(oc.placement, a, room.width, room.depth, clearance=clearance)[1][0]
        for c in oc.relations:
            b = at.get(c.target)
            out["absent" if b is None else c.name] += b is None or not relation(c.name, a, b)[1][0]
    return out


def main(sets: list[str], solvers: list[str]) -> str:
    lines = []
    for ds in sets:
        records = load_dataset(ds, "validation" if ds == "seen" else None)
        step = max(len(records) // 20, 1)
        plans = [r.plan for i, r in enumerate(records) if i % step == step // 2][:16]
        counts = {name: Counter() for name in solvers}
        for name in solvers:
            solver = get_solver(name)
            for plan in plans:
                for seed in (0, 1):
                    counts[name] += unmet(plan, solver.solve(plan, seed=seed))
        kinds = sorted(set().union(*counts.values()), key=lambda k: -max(c[k] for c in counts.values()))
        lines += [f"\n{ds}: unmet constraints per scene ({len(plans)} plans x 2 seeds)\n",
                  "| solver | all | " + " | ".join(kinds) + " |", "| --- " * (len(kinds) + 2) + "|"]
        scenes = 2 * len(plans)
        for name, c in counts.items():
            lines.append(f"| {name} | {sum(c.values()) / scenes:.2f} | "
                         + " | ".join(f"{c[k] / scenes:.2f}" for k in kinds) + " |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    print(main(sys.argv[1].split(","), sys.argv[2].split(",")))
