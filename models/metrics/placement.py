"""Placement metrics (paper Table "Quantitative comparison of object placement performance"), written so
that leaving work undone never earns points (issue 7).

For one plan and its layout:
- CNT  object count fidelity: placed objects / objects the plan asks for.
- SR   task success: 1 when every task object of the plan is placed, else 0. Task objects are the
       anchor, key and inference floor objects and every floor object a task surface object starts on
       (the counter the bread is picked up from: `PlanObject.holds`). n/a (None) for a plan with none.
- Key_NAV share of those task objects the robot can reach from the doorway: some free cell of the
       0.6 m strip in front of the object is connected to a free cell of the doorway. An unplaced one is
       not reached. n/a (None) for a plan with none.
- NAV  the free space a robot of 0.2 m radius can reach from the doorway / all free space, on a 5 cm
       occupancy grid (free: the robot centred there touches no object and no wall). 0 for a layout
       that leaves an object out: the scene asked for was not built, and a room with fewer objects in
       it is always easier to walk through.
- OOB  share of the plan's objects not inside the room: placed with more than 1 cm^2 of footprint
       outside, or not placed at all.
- collisions: placed pairs whose footprints overlap by more than 1 cm^2 (compare it on the plans every
       solver placed completely; `complete` says which).
- constraint satisfaction: satisfied constraints (globals and relations, docs/constraints.md) over all
       readable constraints; a constraint involving an unplaced object counts as not satisfied.
- PTO  placement time per object: the solver's total time / objects in the plan.
Scene-level values are fractions in [0, 1]; the benchmark reports them x 100 like the paper.
"""

from __future__ import annotations

import itertools
from dataclasses import asdict, dataclass

import numpy as np

from models.constraints.evaluate import Poses, placement, relation
from models.energy import navigation as nav
from models.geometry import Footprint, gap, outside_area, overlap_area, wall_clearance
from models.placement.problem import PlacementProblem
from models.values import ConstraintPlan, Layout

AREA_TOL = 1e-4


@dataclass(frozen=True)
class SceneMetrics:
    cnt: float
    sr: float | None
    nav: float
    key_nav: float | None
    oob: float
    collisions: int
    constraint_satisfaction: float
    pto: float
    n_objects: int
    time_s: float
    complete: bool
    n_task: int

    def as_dict(self) -> dict:
        return asdict(self)


def task_targets(plan: ConstraintPlan) -> list[str]:
    """The floor objects the robot must reach for the task (see SR)."""
    return [o.id for o in plan.objects if o.is_task]


def constraint_satisfaction(plan: ConstraintPlan, fps: dict[str, Footprint], problem: PlacementProblem) -> float:
    room = plan.room
    ok = total = 0
    for oid, oc in problem.constraints.objects.items():
        total += 1
        f = fps.get(oid)
        if f is not None:
            clearance = np.array([wall_clearance(f, room.width, room.depth)])
            ok += bool(placement(oc.placement, Poses.one(f.x, f.z, f.rotation, f.width, f.depth), room.width,
                                 room.depth, clearance=clearance)[1][0])
        for c in oc.relations:
            total += 1
            t = fps.get(c.target)
            if f is None or t is None:
                continue
            _, sat = relation(c.name, Poses.one(f.x, f.z, f.rotation, f.width, f.depth),
                              Poses.one(t.x, t.z, t.rotation, t.width, t.depth), gap=np.array([gap(f, t)]))
            ok += bool(sat[0])
    return ok / total if total else 1.0


def reachable_share(blocked: np.ndarray, reachable: np.ndarray) -> float:
    """Free cells reachable from the doorway / all free cells (0 when there is no free cell)."""
    free = int((~blocked).sum())
    return float((reachable & ~blocked).sum() / free) if free else 0.0


def scene_metrics(plan: ConstraintPlan, layout: Layout, problem: PlacementProblem | None = None) -> SceneMetrics:
    problem = problem or PlacementProblem.from_plan(plan)
    room = plan.room
    ids = {o.id for o in plan.objects}
    fps = {p.id: Footprint(p.x, p.z, p.size.x, p.size.z, p.rotation) for p in layout.placements if p.id in ids}
    n = len(plan.objects)
    complete = len(fps) == n
    targets = task_targets(plan)

    grid = nav.Grid(room.width, room.depth)
    blocked = nav.blocked_by_polygons(grid, [f.polygon() for f in fps.values()])
    reachable = nav.reachable_space(grid, blocked, room)
    reached = [k for k in targets if k in fps and nav.can_reach(grid, reachable, fps[k])]

    outside = sum(outside_area(f, room.width, room.depth) > AREA_TOL for f in fps.values()) + (n - len(fps))
    collisions = sum(overlap_area(a, b) > AREA_TOL for a, b in itertools.combinations(fps.values(), 2))
    return SceneMetrics(
        cnt=len(fps) / n if n else 0.0,
        sr=float(all(k in fps for k in targets)) if targets else None,
        nav=reachable_share(blocked, reachable) if complete else 0.0,
        key_nav=len(reached) / len(targets) if targets else None,
        oob=outside / n if n else 0.0,
        collisions=collisions,
        constraint_satisfaction=constraint_satisfaction(plan, fps, problem),
        pto=layout.timing.total_s / n if n else 0.0,
        n_objects=n,
        time_s=layout.timing.total_s,
        complete=complete,
        n_task=len(targets),
    )
