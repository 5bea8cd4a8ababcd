"""The checks a scene must pass before the studio saves it without a question, run after every edit (the studio's,
the API's and the CLI's).

Each finding names what is wrong and which objects cause it: two objects colliding, an object outside
the room, a doorway or the robot's start blocked, a task object the robot cannot reach, and a drop in
Key_NAV or constraint satisfaction against the scene as the placer left it (the reference). Geometry and
navigation come from the project's own functions (models.geometry, models.energy.navigation,
models.metrics), so the studio warns about exactly what the metrics count.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

from shapely.geometry import Point, box

from models.energy import navigation as nav
from models.energy.weights import ROBOT_RADIUS
from models.geometry import Footprint, outside_area, overlap_area
from models.metrics import SceneMetrics, scene_metrics
from models.metrics.placement import AREA_TOL
from models.values import ConstraintPlan, Layout, Scene
from models.values.apartment import Apartment

DROP_TOL = 1e-6  # a metric counts as dropped when it is lower than the reference by more than this


@dataclass(frozen=True)
class Finding:
    kind: str  # collision | out-of-room | door-blocked | start-blocked | unreachable | metric-drop
    text: str
    objects: tuple[str, ...] = ()


def run_checks(plan: ConstraintPlan, layout: Layout, scene: Scene,
               reference: SceneMetrics | None = None) -> tuple[list[Finding], SceneMetrics]:
    """(findings, metrics) of a layout; `reference` is the placer's result the designer started from."""
    room = plan.room
    fps = {p.id: Footprint(p.x, p.z, p.size.x, p.size.z, p.rotation) for p in layout.placements}
    out: list[Finding] = []
    for (a, fa), (b, fb) in itertools.combinations(fps.items(), 2):
        if overlap_area(fa, fb) > AREA_TOL:
            out.append(Finding("collision", f"`{a}` collides with `{b}`", (a, b)))
    for oid, f in fps.items():
        if outside_area(f, room.width, room.depth) > AREA_TOL:
            out.append(Finding("out-of-room", f"`{oid}` is partly outside the room", (oid,)))
    polygons = {oid: f.polygon() for oid, f in fps.items()}
    for door in nav.door_boxes(room):
        blockers = tuple(oid for oid, p in polygons.items() if p.intersection(box(*door)).area > AREA_TOL)
        if blockers:
            out.append(Finding("door-blocked", f"the doorway is blocked by {_names(blockers)}", blockers))
    start = Point(scene.robot_start.x, scene.robot_start.z)
    blockers = tuple(oid for oid, p in polygons.items() if p.distance(start) < ROBOT_RADIUS)
    if blockers:
        out.append(Finding("start-blocked", f"the robot's start is blocked by {_names(blockers)}", blockers))
    grid = nav.Grid(room.width, room.depth)
    reachable = nav.reachable_space(grid, nav.blocked_by_polygons(grid, list(polygons.values())), room)
    for o in plan.objects:
        if o.role in ("anchor", "inference") and o.id in fps and not nav.can_reach(grid, reachable, fps[o.id]):
            out.append(Finding("unreachable", f"the robot cannot reach task object `{o.id}`", (o.id,)))
    metrics = scene_metrics(plan, layout)
    if reference is not None:
        for name, label in (("key_nav", "Key_NAV"), ("constraint_satisfaction", "constraints met")):
            now, before = getattr(metrics, name), getattr(reference, name)
            if now is not None and before is not None and now < before - DROP_TOL:
                out.append(Finding("metric-drop", f"{label} dropped from {100 * before:.0f} % to {100 * now:.0f} %"))
    return out, metrics


def _names(ids: tuple[str, ...]) -> str:
    return ", ".join(f"`{i}`" for i in ids)


def room_label(apartment: Apartment, k: int) -> str:
    """Room `k` (floorplan order) as people name it, e.g. `room 2 (kitchen)`: numbered from 1, as `room|2`."""
    return f"room {k + 1} ({apartment.floorplan.rooms[k].room.type})"


def apartment_findings(apartment: Apartment) -> list[Finding]:
    """Every room's checks (each in its own frame, no metric reference), each named by its room, and the task
    objects the robot cannot reach from the entrance through the doors."""
    out = []
    for k, (plan, layout, scene) in enumerate(zip(apartment.plans, apartment.layouts, apartment.scenes)):
        out += [Finding(f.kind, f"{room_label(apartment, k)}: {f.text}", f.objects)
                for f in run_checks(plan, layout, scene)[0] if f.kind != "unreachable"]
    return out + [Finding("unreachable", f"the robot cannot reach task object `{oid}` from the entrance", (oid,))
                  for oid in apartment.path.unreachable]
