"""The VR start pose (the paper's "VR Position Configuration").

Candidates lie on a circle around the anchor's footprint centre, at a fixed distance for the scene (the
anchor's half-depth plus a person's body radius and a small gap, so a candidate in front of the anchor
stands just clear of it). A candidate is valid when the person standing there
- does not collide: a body disc of BODY_RADIUS stays clear of the walls and of every floor object;
- can reach the anchor: the anchor's usable face (its front for objects used from the front, any side
  otherwise) is within ARM_REACH of the person's centre, with no other object across the arm's path;
- can see it: the line from the eyes (EYE_HEIGHT) to the top of the anchor's centre passes over every
  other object in between.
Valid candidates are ranked by their distance to the room centre (nearest first), as in the paper; the
person faces the anchor's centre and looks down at it. Directions are evenly spaced (every 360 /
N_DIRECTIONS degrees) instead of drawn at random, so the pose is reproducible and no gap is wider.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
import shapely.ops
from shapely.geometry import LineString, Point, Polygon

from models.geometry import Footprint, front
from models.values import AgentPose, Scene, SceneObject, TaskGraph
from models.values.interaction import VRCandidate, VRPoseChoice
from models.world import catalogue

BODY_RADIUS = 0.25  # half a person's shoulder width, metres
STAND_GAP = 0.15  # between the body and the anchor's face, on the circle in front of it
ARM_REACH = 0.75  # from the body's vertical axis to the fingertips, metres
EYE_HEIGHT = 1.6
N_DIRECTIONS = 72
# When nothing on the circle is valid (stools at a counter, a chair at a desk), circles further out are
# tried, while the anchor's face stays within arm's reach: the fixed distance plus 0, 0.15, 0.3 m.
RING_STEPS = (0.0, 0.15, 0.3)
SIGHT_STEP = 0.02  # metres between samples of the line of sight


def footprint(o: SceneObject) -> Footprint:
    return Footprint(o.x, o.z, o.size.x, o.size.z, o.rotation)


def top(o: SceneObject) -> float:
    """Height of an object's top, its children included."""
    return max([o.y + o.size.y / 2] + [c.y + c.size.y / 2 for c in o.children])


def find_anchor(scene: Scene, graph: TaskGraph | None = None) -> tuple[SceneObject, SceneObject] | None:
    """(anchor, the floor object that holds it, itself if on the floor); the object with the anchor role
    first, else any of the anchor's type."""
    graph = graph or scene.task_graph
    if graph is None or graph.anchor is None:
        return None
    anchor_type = graph.anchor.type
    found = []
    for o in scene.objects:
        for obj in [o, *o.children]:
            if obj.type == anchor_type:
                found.append((obj.role != "anchor", obj is not o, obj, o))
    if not found:
        return None
    _, _, obj, holder = min(found, key=lambda t: (t[0], t[1]))
    return obj, holder


def used_from_front(type_name: str) -> bool:
    cat = catalogue()
    return type_name in cat and cat.front_clearance(type_name) > 0


def usable_face(anchor: SceneObject, holder: SceneObject):
    """The part of the anchor a person must reach: its front edge, or its whole footprint."""
    fp = footprint(anchor)
    if anchor is holder and used_from_front(anchor.type):
        corners = fp.corners()  # back-left, back-right, front-right, front-left
        return LineString([corners[2], corners[3]])
    return fp.polygon()


def circle_radius(anchor: SceneObject, holder: SceneObject) -> float:
    """Fixed distance of the candidates from the anchor's centre: far enough that the body clears the
    anchor's holder (itself on the floor) by STAND_GAP in front of it, or, for an object on a holder used
    from any side (a table), at the holder's edge nearest the anchor."""
    fx, fz = front(holder.rotation)
    rx, rz = fz, -fx
    lz = (anchor.x - holder.x) * fx + (anchor.z - holder.z) * fz  # anchor centre in the holder's frame
    lx = (anchor.x - holder.x) * rx + (anchor.z - holder.z) * rz
    to_edge = holder.size.z / 2 - lz
    if anchor is not holder and not used_from_front(holder.type):
        to_edge = min(to_edge, holder.size.z / 2 + lz, holder.size.x / 2 - abs(lx))
    return round(max(to_edge, anchor.size.z / 2) + BODY_RADIUS + STAND_GAP, 4)


def _sight_blocker(eye: tuple[float, float], target: tuple[float, float, float],
                   others: list[tuple[str, Polygon, float]]) -> str | None:
    """Id of an object whose box the eye-to-target line passes through, or None."""
    (ex, ez), (tx, ty, tz) = eye, target
    length = math.hypot(tx - ex, tz - ez)
    n = max(int(length / SIGHT_STEP), 2)
    t = np.linspace(0.0, 1.0, n)
    xs, zs, ys = ex + (tx - ex) * t, ez + (tz - ez) * t, EYE_HEIGHT + (ty - EYE_HEIGHT) * t
    for oid, poly, height in others:
        inside = shapely.contains_xy(poly, xs, zs)
        if (inside & (ys <= height)).any():
            return oid
    return None


def vr_start_pose(scene: Scene, graph: TaskGraph | None = None) -> VRPoseChoice:
    """The best VR start pose for the scene's anchor and the ranked valid alternatives."""
    found = find_anchor(scene, graph)
    if found is None:
        g = graph or scene.task_graph
        anchor_type = g.anchor.type if g is not None and g.anchor is not None else None
        why = "the task graph has no anchor object" if anchor_type is None else \
            f"the anchor {anchor_type} is not in the scene (not placed)"
        return VRPoseChoice(reasons=[why])
    anchor, holder = found
    room = scene.room
    radius = circle_radius(anchor, holder)
    face = usable_face(anchor, holder)
    front_only = isinstance(face, LineString)
    fx, fz = front(holder.rotation)
    anchor_ids = {anchor.id, holder.id} | {c.id for c in anchor.children}
    floor = [(o.id, footprint(o).polygon(), top(o)) for o in scene.objects]
    others = [(oid, poly, h) for oid, poly, h in floor if oid not in anchor_ids]
    target = (anchor.x, anchor.y + anchor.size.y / 2, anchor.z)
    centre = (room.width / 2, room.depth / 2)

    valid: list[VRCandidate] = []
    rejected: dict[str, int] = {}
    tried = 0
    for step in RING_STEPS:
        ring = round(radius + step, 4)
        for k in range(N_DIRECTIONS):
            angle = 360.0 * k / N_DIRECTIONS
            dx, dz = front(angle)
            px, pz = round(anchor.x + ring * dx, 3), round(anchor.z + ring * dz, 3)  # checked as the pose keeps it
            reason = _rejection(px, pz, room.width, room.depth, floor, others, face, front_only, fx, fz, holder,
                                target)
            if reason is not None:
                rejected[reason] = rejected.get(reason, 0) + 1
                continue
            heading = math.degrees(math.atan2(target[0] - px, target[2] - pz)) % 360
            flat = math.hypot(target[0] - px, target[2] - pz)
            horizon = math.degrees(math.atan2(EYE_HEIGHT - target[1], flat))
            pose = AgentPose(x=px, z=pz, rotation=round(heading, 1), horizon=round(horizon, 1))
            valid.append(VRCandidate(pose=pose, distance_to_room_centre=round(math.hypot(px - centre[0], pz - centre[1]), 4),
                                     distance_to_anchor_front=round(face.distance(Point(px, pz)), 4), angle=angle))
        tried += N_DIRECTIONS
        if valid:
            break
    valid.sort(key=lambda c: (c.distance_to_room_centre, c.angle))
    reasons = [] if valid else [f"no valid pose among {tried} candidates at {radius}-{ring} m around "
                                f"{anchor.id}: "
                                + ", ".join(f"{n} {r}" for r, n in sorted(rejected.items(), key=lambda t: -t[1]))]
    return VRPoseChoice(anchor_id=anchor.id, radius=ring, best=valid[0].pose if valid else None,
                        alternatives=valid, candidates_tried=tried, rejected=rejected, reasons=reasons)


def _rejection(px, pz, width, depth, floor, others, face, front_only, fx, fz, holder, target) -> str | None:
    """Why a candidate is not valid (the first failed check), or None."""
    if min(px, pz, width - px, depth - pz) < BODY_RADIUS:
        return "against or outside a wall"
    body = Point(px, pz)
    if any(poly.distance(body) < BODY_RADIUS for _, poly, _ in floor):
        return "collides with an object"
    if front_only and (px - holder.x) * fx + (pz - holder.z) * fz < holder.size.z / 2:
        return "not in front of the anchor"
    if face.distance(body) > ARM_REACH:
        return "anchor out of arm's reach"
    nearest = shapely.ops.nearest_points(face, body)[0]
    reach = LineString([(px, pz), (nearest.x, nearest.y)])
    if any(poly.intersects(reach) for _, poly, _ in others):
        return "arm's path blocked by an object"
    if _sight_blocker((px, pz), target, others) is not None:
        return "line of sight blocked by an object"
    return None
