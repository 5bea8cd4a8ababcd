"""Turning any solver's answer into the Layout of interfaces.md: nothing dropped, every gap explained."""

from __future__ import annotations

from models.placement.problem import PlacementProblem
from models.values import Layout, Placement, Provenance, Timing, Unplaced

NO_ROOM = "no collision-free position left in the room"  # the reason of an object left out for want of room


def make_layout(problem: PlacementProblem, poses: dict[str, tuple[float, float, float]], reasons: dict[str, str],
                solver: str, seed: int, elapsed: float, default_reason: str) -> Layout:
    """`poses`: object id -> (x, z, rotation); objects without a pose get their reason (or the default)."""
    plan = problem.plan
    placements = [Placement(id=o.id, type=o.type, x=round(poses[o.id][0], 4), z=round(poses[o.id][1], 4),
                            rotation=float(poses[o.id][2]) % 360, size=o.size)
                  for o in plan.objects if o.id in poses]
    why = {u.id: u.reason for u in problem.impossible} | reasons
    unplaced = [Unplaced(id=o.id, reason=why.get(o.id, default_reason)) for o in plan.objects if o.id not in poses]
    n = max(len(plan.objects), 1)
    return Layout(plan_id=plan.id, solver=solver, seed=seed, placements=placements, unplaced=unplaced,
                  warnings=list(problem.warnings),
                  timing=Timing(total_s=round(elapsed, 4), per_object_s=round(elapsed / n, 5)),
                  provenance=Provenance(stage="layout", method=solver, seed=seed))
