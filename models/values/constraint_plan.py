"""ConstraintPlan: the input of every placer (interfaces.md, "Constraint plan")."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from models.values.common import Provenance, Size, Value
from models.values.room import Room

PlanRole = Literal["key", "anchor", "inference", "context"]
TASK_ROLES = ("key", "anchor", "inference")


class PlanObject(Value):
    id: str = Field(min_length=1)
    type: str = Field(min_length=1)
    size: Size
    role: PlanRole = "context"
    # roles of the task's surface objects that start on or in this object (the counter the bread must be
    # picked up from holds "key"): the robot has to reach it, so it is a task object too (issue 7)
    holds: list[PlanRole] | None = None

    @property
    def is_task(self) -> bool:
        return self.role in TASK_ROLES or any(r in TASK_ROLES for r in self.holds or ())


class ConstraintPlan(Value):
    id: str = Field(min_length=1)
    room: Room
    objects: list[PlanObject]
    constraints: str = ""
    provenance: Provenance | None = None

    @model_validator(mode="after")
    def _unique_ids(self) -> ConstraintPlan:
        seen: set[str] = set()
        for o in self.objects:
            if o.id in seen:
                raise ValueError(f"object id {o.id!r} appears twice")
            seen.add(o.id)
        return self

    def object(self, object_id: str) -> PlanObject:
        return next(o for o in self.objects if o.id == object_id)
