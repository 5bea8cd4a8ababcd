"""RoomPlan: the room shell plus the selected objects, before any constraint is written."""

from __future__ import annotations

from pydantic import Field, model_validator

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

    @model_validator(mode="after")
    def _mark_task_receptacles(self) -> RoomPlan:
        """A floor object holding a task surface object records the role in `holds` (see PlanObject)."""
        held: dict[str, list[str]] = {}
        for s in self.surface_objects:
            if s.role != "context":
                held.setdefault(s.parent, []).append(s.role)
        marked = [o.model_copy(update={"holds": sorted(set(o.holds or ()) | set(held[o.id]))}) if o.id in held else o
                  for o in self.objects]
        object.__setattr__(self, "objects", marked)  # frozen value: set once, while validating
        return self
