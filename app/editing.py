"""A designer's edits outside the studio (`POST /edit`, `h3ds edit`): the studio's moves, constraint edits and
re-places, on a single room or on one room of an apartment, and carrying an object into another room.

Each edit goes through the same `Pipeline` call as in the studio; an apartment's room is edited in its own frame
and put back with `with_room`, so the robot's path and Key_NAV through the doors follow. The result carries the
edit log as the studio stores it with a version, and the checks the studio runs before saving.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Literal

from pydantic import BaseModel, Field, TypeAdapter

from app.pipeline import Generation, Pipeline, generation_of, pose_of, room_generation
from models.checks import Finding, apartment_findings, room_label, run_checks
from models.metrics import scene_metrics
from models.scene.apartment import with_room
from models.scene.carry import carry, room_holding
from models.values import Placement, Scene
from models.values.apartment import Apartment
from models.values.edit import Edit

MAX_EDITS = 100  # edits in one request
MAX_CONSTRAINT_TEXT = 100_000  # characters of an edited constraint text


class Step(BaseModel):
    """What every edit has: in an apartment, the number of the `room` it edits (from 1); left out, the room of the
    edit before it (the first: the request's room)."""

    room: int | None = Field(None, ge=1, examples=[None])


class Move(Step):
    """One object to a new pose, everything else as it was (a drag or a typed pose in the studio). `x`, `z` in the
    frame of the room edited (its layout's); `rotation` in degrees, the object's own when left out. In an apartment,
    `to_room` (a room number) carries the object into that room, `x`, `z` then in its frame (models.scene.carry)."""

    kind: Literal["move"] = "move"
    object: str = Field(min_length=1, max_length=200, examples=["fridge-0"])
    x: float
    z: float
    rotation: float | None = None
    to_room: int | None = Field(None, ge=1)


class Constraints(Step):
    """The room's constraint text edited (Holodeck's lines): placed again from the first object it changes."""

    kind: Literal["constraints"] = "constraints"
    text: str = Field(max_length=MAX_CONSTRAINT_TEXT, examples=["fridge-0 | edge | near, countertop-0"])


class ReplaceAround(Step):
    """The named objects stay where they are; the placer places the others again around them (the studio's
    *Re-place the rest*)."""

    kind: Literal["replace_around"] = "replace_around"
    objects: list[str] = Field(min_length=1, max_length=200, examples=[["fridge-0"]])


EditStep = Annotated[Move | Constraints | ReplaceAround, Field(discriminator="kind")]
EditList = TypeAdapter(Annotated[list[EditStep], Field(min_length=1, max_length=MAX_EDITS)])  # a script's edits


class EditError(ValueError):
    """An edit that does not fit the scene; `loc` names the field, as a 422 does."""

    def __init__(self, loc: tuple, message: str):
        super().__init__(message)
        self.loc = loc


@dataclass(frozen=True)
class Edited:
    value: Scene | Apartment  # the scene, or the apartment with the room edited put back
    room: Generation  # the room edited last, in its own frame
    log: list[Edit]  # one row per edit, as the studio stores them with a version
    findings: list[Finding]  # the checks after the edits (a single room's against the scene before them)


def room_of(value: Scene | Apartment, room: int | None, loc: tuple = ("room",)) -> Generation:
    """The room to edit: the scene, or room number `room` (from 1, as `room|N`) of an apartment (`loc`: the field
    that gave it)."""
    if isinstance(value, Scene):
        if room is not None:
            raise EditError(loc, f"scene {value.id} is a single room: leave room out")
        try:
            return generation_of(value)
        except ValueError as e:
            raise EditError(("scene",), str(e)) from e
    if room is None or not 1 <= room <= len(value.plans):
        given = "none was given" if room is None else f"not {room}"
        raise EditError(loc, f"apartment {value.id} has rooms 1-{len(value.plans)}: say which one to edit "
                                   f"({given})")
    return room_generation(value, room - 1)


def generated_seed(scene: Scene) -> int:
    """The seed a scene was generated with (what the studio re-plans with)."""
    return next((p.seed for p in scene.provenance if p.stage == "scene" and p.seed is not None), 0)


def apply_edits(pipeline: Pipeline, value: Scene | Apartment, edits: list[EditStep], room: int | None = None,
                seed: int | None = None, solver: str | None = None) -> Edited:
    """`edits` in order on the scene or on room `room` of the apartment (left out: the room of the object the first
    edit names; after a carry, the room the object went to; an edit's own `room` switches to that one); `seed`: the one
    it was generated with if left out. Raises EditError naming the edit that does not fit; nothing is changed then."""
    loc = ("room",)
    if isinstance(value, Apartment) and room is None and edits:
        first = edits[0]
        room, loc = (first.room, ("edits", 0, "room")) if first.room else (_room_named(value, first), loc)
    gen = room_of(value, room, loc)
    seed = generated_seed(gen.scene) if seed is None else seed
    before, log = gen, []
    for i, edit in enumerate(edits):
        if edit.room is not None and edit.room != room:
            if isinstance(value, Scene):
                raise EditError(("edits", i, "room"), f"scene {value.id} is a single room: leave room out")
            value, room = with_room(value, room - 1, gen.plan, gen.layout, seed), edit.room  # the edits so far kept
            gen = room_of(value, room, ("edits", i, "room"))
        where = room_label(value, room - 1) if isinstance(value, Apartment) else f"scene {value.id}"
        if isinstance(edit, Move) and edit.to_room is not None:
            if isinstance(value, Scene):
                raise EditError(("edits", i, "to_room"), f"scene {value.id} is a single room: leave to_room out")
            house = with_room(value, room - 1, gen.plan, gen.layout, seed)  # the edits so far, then the carry
            value, row = _carry(house, room, edit, seed, ("edits", i), where)
            room = edit.to_room  # as in the studio, the edits that follow are in the room it went to
            gen = room_generation(value, room - 1)
        else:
            gen, row = _apply(pipeline, gen, edit, seed, solver, ("edits", i), where)
        log.append(row)
    if isinstance(value, Scene):
        found, _ = run_checks(gen.plan, gen.layout, gen.scene, scene_metrics(before.plan, before.layout))
        return Edited(gen.scene, gen, log, found)
    house = with_room(value, room - 1, gen.plan, gen.layout, seed)
    return Edited(house, gen, log, apartment_findings(house))


def _room_named(apartment: Apartment, edit: EditStep) -> int | None:
    """The room (from 1) holding the object an edit names first, if it names one the apartment holds."""
    named = edit.object if isinstance(edit, Move) else edit.objects[0] if isinstance(edit, ReplaceAround) else None
    try:
        return room_holding(apartment, named) + 1 if named else None
    except ValueError:
        return None


def _carry(house: Apartment, room: int, edit: Move, seed: int, loc: tuple, where: str) -> tuple[Apartment, Edit]:
    """A move that carries an object of room `room` into room `edit.to_room` (its frame)."""
    if not 1 <= edit.to_room <= len(house.plans) or edit.to_room == room:
        raise EditError((*loc, "to_room"), f"apartment {house.id} has rooms 1-{len(house.plans)}: carry "
                                           f"{edit.object} to one other than room {room}, not {edit.to_room}")
    placed = house.layouts[room - 1].placement(edit.object)
    if placed is None:
        raise EditError((*loc, "object"), f"{edit.object} is not a placed object of {where}")
    to = edit.to_room - 1
    dest = house.plans[to].room
    if not (0 <= edit.x <= dest.width and 0 <= edit.z <= dest.depth):
        raise EditError(loc, f"({edit.x}, {edit.z}) is outside the {dest.width} x {dest.depth} m room of "
                             f"{room_label(house, to)} (x, z are in that room's own frame)")
    rotation = placed.rotation if edit.rotation is None else edit.rotation
    carried, new_id = carry(house, edit.object, to, edit.x, edit.z, rotation, seed)
    return carried, carry_row(edit.object, room, placed, new_id, edit.to_room, carried.layouts[to].placement(new_id))


def move_row(object_id: str, before: Placement, x: float, z: float, rotation: float) -> Edit:
    """The edit log's row of a move (room frame), as the studio and the API store it."""
    return Edit("move", object_id, [before.x, before.z, before.rotation], [round(x, 3), round(z, 3), rotation % 360])


def carry_row(object_id: str, room: int, before: Placement, new_id: str, to_room: int, after: Placement) -> Edit:
    """The edit log's row of a carry: rooms numbered from 1, each pose in its room's frame."""
    return Edit("carry", object_id, {"room": room, "pose": list(pose_of(before))},
                {"room": to_room, "id": new_id, "pose": list(pose_of(after))})


def _apply(pipeline: Pipeline, gen: Generation, edit: EditStep, seed: int, solver: str | None, loc: tuple,
           where: str) -> tuple[Generation, Edit]:
    ids = {o.id for o in gen.plan.objects}
    if isinstance(edit, Move):
        p = gen.layout.placement(edit.object)
        if p is None:
            problem = "is not an object of" if edit.object not in ids else "was left out of the layout of"
            raise EditError((*loc, "object"), f"{edit.object} {problem} {where}; its placed objects: "
                                              f"{', '.join(q.id for q in gen.layout.placements)}")
        w, d = gen.plan.room.width, gen.plan.room.depth
        if not (0 <= edit.x <= w and 0 <= edit.z <= d):
            raise EditError(loc, f"({edit.x}, {edit.z}) is outside the {w} x {d} m room of {where} (x, z are in the "
                                 "room's own frame)")
        rotation = p.rotation if edit.rotation is None else edit.rotation
        moved = pipeline.move(gen, edit.object, edit.x, edit.z, rotation, seed)
        return moved, move_row(edit.object, p, edit.x, edit.z, rotation)
    if isinstance(edit, Constraints):
        return pipeline.replan(gen, edit.text, seed, solver), Edit("constraints", "plan", gen.plan.constraints,
                                                                    edit.text)
    if unknown := [o for o in edit.objects if o not in ids]:
        raise EditError((*loc, "objects"), f"not objects of {where}: {', '.join(unknown)}")
    try:
        replaced = pipeline.replace_around(gen, edit.objects, seed, solver)
    except ValueError as e:  # none of them is placed
        raise EditError((*loc, "objects"), str(e)) from e
    return replaced, Edit("re-place", ", ".join(edit.objects), None, None)
