"""The room (or the apartment) as it stood after each placement step, for the studio's step animation and its energy
plot to show what the placer did: each object where its step put it, moved by each repair step, taken up when the
placer solves its room again from empty (`PlacementStep.restart`, models.placement.reorder), and, at its last step,
where it stands now (a designer's move since the placing shows there). In an apartment each room is solved on its
own: `room_of` tells which room an object is in, and a restart takes up only that room's objects."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

from models.energy.exact import layout_energy
from models.placement import PlacementProblem, PlacementStep
from models.values import ConstraintPlan, Placement, Scene, SceneObject

Pose = tuple[float, float, float]  # x, z, Unity yaw
RoomOf = Callable[[str], str]  # object id -> the room it is placed in


def one_room(_object_id: str) -> str:
    return ""


def _latest(steps: Sequence[PlacementStep], shown: int, room_of: RoomOf) -> dict[str, int]:
    """Each object stepped in its room's current solve within the first `shown` steps -> its latest step's index, in
    the order they came (a restart takes up its room's objects)."""
    latest: dict[str, int] = {}
    for k, step in enumerate(steps[:shown]):
        if step.restart:
            room = room_of(step.object_id)
            latest = {oid: i for oid, i in latest.items() if room_of(oid) != room}
        latest[step.object_id] = k
    return latest


def standing(steps: Sequence[PlacementStep], shown: int, room_of: RoomOf = one_room) -> dict[str, Pose | None]:
    """The objects standing after the first `shown` steps, in the order they came: each with the pose its latest
    step gave it, or None at its last step of all (it stands where it is now); an object that step left out is
    not there."""
    last = {s.object_id: k for k, s in enumerate(steps)}
    return {oid: None if k == last[oid] else (steps[k].x, steps[k].z, steps[k].rotation)
            for oid, k in _latest(steps, shown, room_of).items() if steps[k].x is not None}


def to_come(steps: Sequence[PlacementStep], shown: int, room_of: RoomOf = one_room) -> set[str]:
    """The objects a later step places that do not stand after the first `shown` steps: the placer has still to
    place them, so the energy of the room then leaves them pending (not charged as left out)."""
    return {s.object_id for s in steps[shown:]} - set(standing(steps, shown, room_of))


def repeated(steps: Sequence[PlacementStep], shown: int, room_of: RoomOf = one_room) -> bool:
    """Was the object of step `shown` (1-based) placed before in the same solve of its room (a repair's step)?"""
    step = steps[shown - 1]
    return not step.restart and step.object_id in _latest(steps, shown - 1, room_of)


def moved_to(obj: SceneObject, pose: Pose) -> SceneObject:
    """`obj` moved and turned to a floor pose, what stands on it carried along."""
    x, z, rotation = pose
    turn = math.radians(rotation - obj.rotation)
    cos, sin = math.cos(turn), math.sin(turn)

    def carried(child: SceneObject) -> SceneObject:
        dx, dz = child.x - obj.x, child.z - obj.z  # a yaw turns +z (forward) towards +x (right)
        return child.model_copy(update={"x": x + cos * dx + sin * dz, "z": z - sin * dx + cos * dz,
                                        "rotation": (child.rotation + rotation - obj.rotation) % 360})

    return obj.model_copy(update={"x": x, "z": z, "rotation": rotation,
                                  "children": [carried(c) for c in obj.children]})


def room_at(scene: Scene, steps: Sequence[PlacementStep], shown: int, room_of: RoomOf = one_room
            ) -> tuple[Scene, set[str] | None]:
    """`scene` as it stood after its first `shown` placement `steps` (in the scene's frame), and the ids on show
    then (the objects standing and what stands on them); (`scene`, None: everything) once every step is shown."""
    if shown >= len(steps):
        return scene, None
    now = standing(steps, shown, room_of)
    objects = [moved_to(o, now[o.id]) if now.get(o.id) is not None else o for o in scene.objects]
    visible = {i for o in objects if o.id in now for i in (o.id, *(c.id for c in o.children))}
    return scene.model_copy(update={"objects": objects}), visible


def placements_at(placements: Sequence[Placement], steps: Sequence[PlacementStep], shown: int) -> list[Placement]:
    """A room's `placements` as they stood after its first `shown` steps (see `room_at`)."""
    by_id = {p.id: p for p in placements}
    return [by_id[oid] if pose is None else by_id[oid].model_copy(update=dict(zip(("x", "z", "rotation"), pose)))
            for oid, pose in standing(steps, shown).items() if oid in by_id]


def energy_after_steps(rooms: Sequence[tuple[ConstraintPlan, Sequence[Placement]]], steps: Sequence[PlacementStep],
                       room_of: RoomOf = one_room) -> list[dict[str, float]]:
    """The energy terms (exact energy) after each step, summed over the `rooms` (plan, placements now; an apartment's
    are solved one after another): each room as it stood then, the objects still to come pending, as the placer's
    own step sees them. A room is scored again only at its own steps (a room without objects scores 0)."""
    of_room: dict[str, list[PlacementStep]] = {}
    for step in steps:
        of_room.setdefault(room_of(step.object_id), []).append(step)
    plans = {room_of(plan.objects[0].id): (plan, placements, PlacementProblem.from_plan(plan))
             for plan, placements in rooms if plan.objects}
    terms = {room: layout_energy(plan, [], problem, pending=to_come(of_room.get(room, []), 0)).as_dict()
             for room, (plan, _, problem) in plans.items()}
    shown = dict.fromkeys(of_room, 0)
    rows = []
    for step in steps if terms else ():
        room = room_of(step.object_id)
        shown[room] += 1
        if room in plans:
            plan, placements, problem = plans[room]
            terms[room] = layout_energy(plan, placements_at(placements, of_room[room], shown[room]), problem,
                                        pending=to_come(of_room[room], shown[room])).as_dict()
        rows.append({t: sum(r[t] for r in terms.values()) for t in next(iter(terms.values()))})
    return rows
