"""Layout -> Scene.

Each placed floor object gets the real asset its plan size came from; each surface object goes on
(or, for fridges, microwaves, safes and the like, in) its parent as an AI2-THOR child, spread over
the parent's top so that no two children share a spot, a task object where the robot can come near it
(`_spots`). If a parent could not be placed, its children
move to another placed receptacle that accepts them, or are reported unplaced. The robot starts just
inside a door facing in (the door that reaches the most task objects, `robot_start`); the VR user starts
at models.interaction.vr_start_pose's best pose (reaching and seeing the anchor), with the other valid
poses as alternatives.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Sequence

import numpy as np
from scipy import ndimage

from models.energy import navigation as nav
from models.geometry import boxes, front
from models.interaction.robot_plan import APPROACH
from models.interaction.vr_pose import vr_start_pose
from models.values import (
    AgentPose,
    Layout,
    Placement,
    Provenance,
    Room,
    RoomPlan,
    Scene,
    SceneObject,
    SurfaceObject,
    TaskGraph,
    Unplaced,
)
from models.world import catalogue
from models.world.catalogue import HOST_TYPES

INSIDE_TYPES = {"Fridge", "Microwave", "Safe", "Cabinet", "Drawer", "GarbageCan", "Box", "Toilet", "SinkBasin",
                "BathtubBasin", "Sink", "LaundryHamper", "WashingMachine", "ClothesDryer"}
ROBOT_INSET = 0.6
ALONG = 17  # spots tried along a host's top for a task object that stands on it alone


def _slots(parent: Placement, n: int) -> list[tuple[float, float]]:
    """n spots spread along the parent's width, in world (x, z)."""
    fx, fz = front(parent.rotation)
    rx, rz = fz, -fx
    usable = parent.size.x * 0.8
    spots = []
    for k in range(n):
        lateral = -usable / 2 + usable * (k + 0.5) / n
        spots.append((parent.x + rx * lateral, parent.z + rz * lateral))
    return spots


def _spots(parent: Placement, kids: list[SurfaceObject],
           far: Callable[[float, float], float]) -> list[tuple[float, float]]:
    """The kids' spots: `_slots` in order, unless a task object's slot lies beyond the robot plan's `APPROACH` of the
    free floor the robot reaches (`far`: distance from a point to it). Then the task objects take the slots nearest
    that floor, the others the rest in order; a task object alone takes the spot along the top nearest it."""
    spots = _slots(parent, len(kids))
    task = [k for k, c in enumerate(kids) if c.role != "context"]
    if all(far(*spots[k]) <= APPROACH for k in task):
        return spots
    if len(kids) == 1:
        return [min(_slots(parent, ALONG), key=lambda xz: (far(*xz), abs(xz[0] - parent.x) + abs(xz[1] - parent.z)))]
    nearest = sorted(range(len(spots)), key=lambda k: far(*spots[k]))
    given = dict(zip(task, nearest))
    rest = iter(k for k in range(len(spots)) if k not in given.values())
    return [spots[given[k]] if k in given else spots[next(rest)] for k in range(len(kids))]


def _far_from_reach(room: Room, placements: Sequence[Placement]) -> Callable[[float, float], float]:
    """Distance from a point of the room to the nearest free cell the robot reaches from a door (Key_NAV's grid,
    objects as axis-aligned boxes); infinite when it reaches none."""
    grid = nav.Grid(room.width, room.depth)
    blocked = nav.blocked_by_boxes(grid, footprint_boxes(placements))
    reach = nav.reachable_space(grid, blocked, room)
    if not reach.any():
        return lambda x, z: float("inf")
    dist = ndimage.distance_transform_edt(~reach) * grid.cell

    def far(x: float, z: float) -> float:
        i = min(max(int(x // grid.cell), 0), dist.shape[0] - 1)
        j = min(max(int(z // grid.cell), 0), dist.shape[1] - 1)
        return float(dist[i, j])

    return far


def _child(obj: SurfaceObject, parent: Placement, parent_type: str, spot: tuple[float, float], asset_id: str,
           rotation: float) -> SceneObject:
    if parent_type in INSIDE_TYPES:
        y = min(parent.size.y * 0.5, parent.size.y - obj.size.y / 2)
    else:
        y = parent.size.y + obj.size.y / 2
    return SceneObject(id=obj.id, type=obj.type, asset_id=asset_id, role=obj.role, x=round(spot[0], 4),
                       y=round(max(y, obj.size.y / 2), 4), z=round(spot[1], 4), rotation=rotation, size=obj.size)


def robot_start(plan: RoomPlan, objects: Sequence[SceneObject] = ()) -> AgentPose:
    """Just inside a door, facing in: of the room's doors, the one from whose free floor the robot comes within
    `APPROACH` of the most task objects (floor objects and what stands on or in them, as the robot plan asks), then
    reaches the most free floor; the first door on a tie. A room's second door may open onto a bed across the way."""
    room = plan.room
    if not room.doors:
        return AgentPose(x=room.width / 2, z=room.depth / 2, rotation=0)
    return inside_door(room, _entry(room, objects))


def inside_door(room: Room, k: int) -> AgentPose:
    """Just inside the room's door `k`, facing in."""
    d = room.doors[k]
    return {"south": AgentPose(x=d.center, z=ROBOT_INSET, rotation=0),
            "north": AgentPose(x=d.center, z=room.depth - ROBOT_INSET, rotation=180),
            "west": AgentPose(x=ROBOT_INSET, z=d.center, rotation=90),
            "east": AgentPose(x=room.width - ROBOT_INSET, z=d.center, rotation=270)}[d.wall]


def _entry(room: Room, objects: Sequence[SceneObject]) -> int:
    """The index of the door `robot_start` enters by. Objects as their axis-aligned boxes (exact at quarter turns),
    on Key_NAV's grid: about 0.6 ms for a room of two doors."""
    if len(room.doors) < 2 or not objects:
        return 0
    grid = nav.Grid(room.width, room.depth)
    blocked = nav.blocked_by_boxes(grid, footprint_boxes(objects))
    tasks = footprint_boxes([o for o in objects if o.role != "context"] + [c for o in objects for c in o.children
                                                                           if c.role != "context"])
    doors = nav.door_masks(grid, room)
    gx, gz = grid.mesh()
    near = [np.hypot(np.maximum(0, np.maximum(b[0] - gx, gx - b[2])), np.maximum(0, np.maximum(b[1] - gz, gz - b[3])))
            <= APPROACH for b in tasks]  # the cells within the robot plan's approach of each task object

    def score(k: int) -> tuple[int, int, int]:
        reach = nav.reachable_from(blocked, doors[k])
        return sum(bool((reach & m).any()) for m in near), int(reach.sum()), -k

    return max(range(len(room.doors)), key=score)


def footprint_boxes(objects: Sequence[SceneObject | Placement]) -> np.ndarray:
    """(N, 4) axis-aligned boxes [xmin, zmin, xmax, zmax] around the objects' footprints."""
    return boxes([o.x for o in objects], [o.z for o in objects], [o.size.x for o in objects],
                 [o.size.z for o in objects], [o.rotation for o in objects]).reshape(-1, 4)


def assemble_scene(plan: RoomPlan, layout: Layout, graph: TaskGraph | None = None, seed: int = 0,
                   constraints: str | None = None) -> Scene:
    cat = catalogue()
    rng = random.Random(seed)
    warnings = list(layout.warnings)
    plan_objects = {o.id: o for o in plan.objects}
    placed = {p.id: p for p in layout.placements}

    children: dict[str, list[SurfaceObject]] = {pid: [] for pid in placed}
    unplaced = list(layout.unplaced)
    for s in plan.surface_objects:
        parent_id = s.parent if s.parent in placed else None
        if parent_id is None:
            accepting = sorted((cat.host(p.type).contents.get(s.type, 0.0), pid) for pid, p in placed.items())
            accepting = [a for a in accepting if a[0] > 0]
            if accepting:
                parent_id = accepting[-1][1]
                warnings.append(f"{s.id} moved to {parent_id}: its receptacle {s.parent} could not be placed")
            else:
                unplaced.append(Unplaced(id=s.id, reason=f"its receptacle {s.parent} could not be placed"))
                continue
        children[parent_id].append(s)

    objects = []
    far = _far_from_reach(plan.room, layout.placements)
    for pid, p in placed.items():
        obj = plan_objects.get(pid)
        asset = cat.pick_asset(p.type, rng, fits=(p.size.x, p.size.z))
        if p.type in HOST_TYPES:
            warnings.append(f"{pid}: AI2-THOR has no {p.type} asset of its own; exported as "
                            f"{cat.host(p.type).name} asset {asset.asset_id}")
        kids = [_child(c, p, p.type, spot, cat.pick_asset(c.type, rng, fits=(c.size.x, c.size.z)).asset_id,
                       p.rotation)
                for c, spot in zip(children[pid], _spots(p, children[pid], far))]
        objects.append(SceneObject(id=pid, type=p.type, asset_id=asset.asset_id,
                                   role=obj.role if obj else "context", x=p.x, y=round(p.size.y / 2, 4), z=p.z,
                                   rotation=p.rotation, size=p.size, children=kids))
    room = plan.room
    provenance = [pv for pv in (graph.provenance if graph else None, plan.provenance, layout.provenance) if pv]
    scene = Scene(id=plan.id, room=room, task_graph=graph, objects=objects, unplaced=unplaced,
                  robot_start=robot_start(plan, objects), warnings=warnings, room_plan=plan,
                  constraints=constraints,
                  provenance=provenance + [Provenance(stage="scene", method="assemble", seed=seed)])
    vr = vr_start_pose(scene)
    missing_pose = [f"VR start pose: {r}" for r in vr.reasons] if graph is not None and graph.anchor else []
    return scene.model_copy(update={"vr_anchor": vr.best, "vr_alternatives": [c.pose for c in vr.alternatives[1:]],
                                    "warnings": warnings + missing_pose})

