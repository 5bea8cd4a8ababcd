"""Why Plan2Place leaves objects off their wall on `dense` (the `edge` constraints of unmet-by-kind.md): for each
object whose `edge` is broken in the final layout, whether a wall pose meeting `edge` exists with the other objects
where they are, under the strict hard filter, only with front clearances relaxed, or only if objects made way;
and, where a strict one exists, why the polish did not take it (it moves an object only if that meets strictly
more of the constraints involving it, at no energy cost). 16 `dense` plans off the benchmarks' samples
(`i % step == step // 2`), seed 0. From the root: python app/bench/results/plan2place/edge-broken.py > edge-broken.md"""

from collections import Counter

import numpy as np

from models.constraints.evaluate import Poses, placement, wall_clearance
from models.datasets import load_dataset
from models.energy.exact import layout_energy
from models.energy.vectorised import CandidateEnergy
from models.geometry import SweptBoxes
from models.placement.base import get_solver
from models.placement.greedy import Episode, hard_filter
from models.placement.polish import met, met_among


def on_wall(poses: Poses, room) -> np.ndarray:
    return placement("edge", poses, room.width, room.depth, clearance=wall_clearance(poses, room.width, room.depth))[1]


def reasons(plan, layout) -> Counter:
    ep, room, out = Episode(plan), plan.room, Counter()
    placed = [ep.scorer.place(plan.object(p.id), p.x, p.z, p.rotation) for p in layout.placements]
    energy = layout_energy(plan, layout.placements).total
    for p in placed:
        oc = ep.problem.constraints.objects.get(p.id)
        if oc is None or oc.placement != "edge" or on_wall(Poses.one(p.x, p.z, p.rotation, p.width, p.depth), room)[0]:
            continue
        obj, others = plan.object(p.id), [q for q in placed if q is not p]
        cands, body = ep.scorer.bodies(obj)
        wall = on_wall(Poses(cands[:, 0], cands[:, 1], cands[:, 2], obj.size.x, obj.size.z), room)
        strict = hard_filter(ep.scorer, obj, others, cands, SweptBoxes(body), True)[0] & wall
        if not strict.any():
            relaxed = hard_filter(ep.scorer, obj, others, cands, SweptBoxes(body), False)[0] & wall
            out["no strict wall pose: one only with a clearance relaxed" if relaxed.any()
                else "no strict wall pose: objects would have to make way"] += 1
            continue
        idx = np.flatnonzero(strict)
        gain = met(ep, p.id, idx, others) - met_among(ep, placed, {p.id})
        if gain.max() <= 0:
            out["a strict wall pose, but it meets no more constraints in all (relations lost)"] += 1
            continue
        terms = CandidateEnergy(ep.problem, others).score(obj, cands[idx[gain > 0]], nav_mode="exact")
        out["a strict wall pose meeting more, but the energy rises at each" if terms["total"].min() > energy + 1e-9
            else "a strict wall pose meeting more at no energy cost (the polish missed it)"] += 1
    return out


def main() -> str:
    records = load_dataset("dense")
    step = max(len(records) // 20, 1)
    plans = [r.plan for i, r in enumerate(records) if i % step == step // 2][:16]
    solver, total = get_solver("plan2place"), Counter()
    for plan in plans:
        total += reasons(plan, solver.solve(plan, seed=0))
    lines = [f"Objects off their wall (`edge` broken) in Plan2Place's layouts of {len(plans)} `dense` plans, seed 0: "
             f"{sum(total.values())}", "", "| why | objects |", "| --- | --- |"]
    lines += [f"| {k} | {v} |" for k, v in total.most_common()]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    print(main())
