"""Layouts of every room -> Apartment.

Each room is assembled as a single-room Scene in its own frame (real assets, children, warnings); the
robot starts just inside the entrance, the VR user in the anchor's room (both in the house frame), and
Key_NAV, E_nav and the robot's path are measured across the rooms through the doors.
"""

from __future__ import annotations

from models.energy.house_navigation import house_navigation
from models.geometry import Footprint
from models.scene.assemble import assemble_scene, inside_door
from models.values import AgentPose, ConstraintPlan, Layout, SceneObject, TaskGraph, Unplaced
from models.values.apartment import OUTSIDE, Apartment, Doorway, HousePlan, HouseRoom

VISIT_ORDER = {"key": 0, "inference": 1, "anchor": 2}


def shifted(obj: SceneObject, hr: HouseRoom) -> SceneObject:
    """An object (and its children) moved from its room's frame to the house frame."""
    return obj.model_copy(update={"x": round(obj.x + hr.x, 4), "z": round(obj.z + hr.z, 4),
                                  "children": [shifted(c, hr) for c in obj.children]})


def house_pose(pose: AgentPose, hr: HouseRoom) -> AgentPose:
    return pose.model_copy(update={"x": round(pose.x + hr.x, 4), "z": round(pose.z + hr.z, 4)})


def entrance_start(hr: HouseRoom, entrance: Doorway) -> AgentPose:
    """Just inside the apartment's entrance, facing in (a room's own start may be by a door between rooms)."""
    mid = entrance.middle
    starts = [house_pose(inside_door(hr.room, k), hr) for k in range(len(hr.room.doors))]
    return min(starts, key=lambda p: abs(p.x - mid[0]) + abs(p.z - mid[1]))


def house_objects(apartment: Apartment) -> list[SceneObject]:
    """Every floor object of every room, in the house frame."""
    return [shifted(o, hr) for hr, s in zip(apartment.floorplan.rooms, apartment.scenes) for o in s.objects]


def visit_order(plans: list[ConstraintPlan]) -> list[str]:
    """The task objects the robot must reach: where the key object starts, then the tools, the anchor last."""
    def rank(o) -> int:
        return min(VISIT_ORDER.get(r, 3) for r in [o.role, *(o.holds or [])])
    tasks = [o for p in plans for o in p.objects if o.is_task]
    return [o.id for o in sorted(tasks, key=rank)]


def assemble_apartment(plan: HousePlan, plans: list[ConstraintPlan], layouts: list[Layout], graph: TaskGraph,
                       seed: int = 0) -> Apartment:
    rooms = plan.floorplan.rooms
    anchor_room = plan.assignment.get(graph.anchor.type) if graph.anchor else None
    scenes = [assemble_scene(rp, layout, graph if hr.id == anchor_room else None, seed, cp.constraints)
              for hr, rp, cp, layout in zip(rooms, plan.room_plans, plans, layouts)]
    entrance = next(d for d in plan.floorplan.doors if d.id == plan.floorplan.entrance)
    first = next(i for i, hr in enumerate(rooms) if hr.id in entrance.rooms and hr.id != OUTSIDE)
    start = entrance_start(rooms[first], entrance)
    footprints = {p.id: Footprint(p.x + hr.x, p.z + hr.z, p.size.x, p.size.z, p.rotation)
                  for hr, layout in zip(rooms, layouts) for p in layout.placements}
    navigation = house_navigation(plan.floorplan, footprints, visit_order(plans), (start.x, start.z))
    vr = None
    if anchor_room is not None:
        k = next(i for i, hr in enumerate(rooms) if hr.id == anchor_room)
        vr = house_pose(scenes[k].vr_anchor, rooms[k]) if scenes[k].vr_anchor else None
    unplaced = [Unplaced(id=u.id, reason=f"{u.reason} (in the {hr.room.type}, {hr.id})")
                for hr, s in zip(rooms, scenes) for u in s.unplaced]
    warnings = [f"{hr.id} ({hr.room.type}): {w}" for hr, s in zip(rooms, scenes) for w in s.warnings]
    warnings += [f"the robot cannot reach {oid} from the entrance" for oid in navigation.path.unreachable]
    return Apartment(id=plan.id, task_graph=graph, plan=plan, layouts=layouts, plans=plans,
                     scenes=scenes, robot_start=start,
                     vr_anchor=vr, anchor_room=anchor_room, key_nav=navigation.key_nav, e_nav=navigation.e_nav,
                     path=navigation.path, unplaced=unplaced, warnings=warnings + plan.warnings)


def with_room(apartment: Apartment, k: int, plan: ConstraintPlan, layout: Layout, seed: int = 0) -> Apartment:
    """The apartment with room `k` (floorplan order) placed again from an edited plan and layout, the others as
    they were: assembled anew, so the robot's path, Key_NAV and the warnings follow the edit across the doors."""
    if not 0 <= k < len(apartment.plans):
        raise ValueError(f"the apartment has rooms 0-{len(apartment.plans) - 1}; room {k} was given")
    if {o.id for o in plan.objects} != {o.id for o in apartment.plans[k].objects}:
        raise ValueError(f"the edited plan {plan.id} does not hold the objects of room {k + 1} of {apartment.id}")
    plans = [plan if i == k else p for i, p in enumerate(apartment.plans)]
    layouts = [layout if i == k else lay for i, lay in enumerate(apartment.layouts)]
    return assemble_apartment(apartment.plan, plans, layouts, apartment.task_graph, seed)
