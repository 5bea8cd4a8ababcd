"""Placement metrics (paper Table "Quantitative comparison of object placement performance").

For one plan and its layout:
- CNT  object count fidelity: placed objects / objects the plan asks for.
- SR   task success: 1 when every anchor and inference object of the plan is placed, else 0.
- NAV  scene navigability (SceneEval's definition): on an occupancy grid of 5 cm cells where a cell is
       free if a robot of 0.2 m radius centred there touches no object and no wall, the largest
       connected (4-neighbour) free region divided by all free space.
- Key_NAV key-object navigability: share of the anchor and inference objects the robot can reach from
       the doorway, i.e. some free cell of the 0.6 m strip in front of the object is connected to a
       free cell of the doorway (A*'s question, answered for all objects at once).
- OOB  share of placed objects with more than 1 cm^2 of footprint outside the room.
- collisions: number of placed pairs whose footprints overlap by more than 1 cm^2.
- constraint satisfaction: satisfied constraints (globals and relations, constraints.md's table) over
       all readable constraints; a constraint involving an unplaced object counts as not satisfied.
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
    sr: float
    nav: float
    key_nav: float
    oob: float
    collisions: int
    constraint_satisfaction: float
    pto: float
    n_objects: int
    time_s: float

    def as_dict(self) -> dict:
        return asdict(self)


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


def scene_metrics(plan: ConstraintPlan, layout: Layout, problem: PlacementProblem | None = None) -> SceneMetrics:
    problem = problem or PlacementProblem.from_plan(plan)
    room = plan.room
    fps = {p.id: Footprint(p.x, p.z, p.size.x, p.size.z, p.rotation) for p in layout.placements}
    n = len(plan.objects)
    key = [o.id for o in plan.objects if o.role in ("anchor", "inference")]

    grid = nav.Grid(room.width, room.depth)
    blocked = nav.blocked_by_polygons(grid, [f.polygon() for f in fps.values()])
    reachable = nav.reachable_space(grid, blocked, room)
    reached = [k for k in key if k in fps and nav.can_reach(grid, reachable, fps[k])]

    oob = sum(outside_area(f, room.width, room.depth) > AREA_TOL for f in fps.values())
    collisions = sum(overlap_area(a, b) > AREA_TOL for a, b in itertools.combinations(fps.values(), 2))
    return SceneMetrics(
        cnt=len(fps) / n if n else 1.0,
        sr=float(all(k in fps for k in key)),
        nav=nav.largest_free_share(blocked),
        key_nav=len(reached) / len(key) if key else 1.0,
        oob=oob / len(fps) if fps else 0.0,
        collisions=collisions,
        constraint_satisfaction=constraint_satisfaction(plan, fps, problem),
        pto=layout.timing.total_s / n if n else 0.0,
        n_objects=n,
        time_s=layout.timing.total_s,
    )
