"""RoomPlan: the room shell plus the selected objects, before any constraint is written."""

from __future__ import annotations

from pydantic import Field

from models.values.common import Provenance, Size, Value
from models.values.constraint_plan import PlanObject
from models.values.room import Room


class SurfaceObject(Value):
    """An object that stands on or in a floor object (an AI2-THOR child), such as the bread on the counter."""

    id: str
    type: str
    size: Size
    role: str = "context"
    parent: str


class RoomPlan(Value):
    id: str
    room: Room
    objects: list[PlanObject]
    surface_objects: list[SurfaceObject] = Field(default_factory=list)
    provenance: Provenance | None = None
