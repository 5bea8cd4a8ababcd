"""TaskGraph: the task scene graph of an instruction (interfaces.md, "Task scene graph")."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, field_validator

from models.values.common import Provenance, Value

Role = Literal["key", "anchor", "inference"]
ROLES: tuple[str, ...] = ("key", "anchor", "inference")
TASK_TYPES: tuple[str, ...] = (
    "pick_and_place_simple",
    "look_at_obj_in_light",
    "pick_cool_then_place_in_recep",
    "pick_heat_then_place_in_recep",
)
RELATIONS: tuple[str, ...] = ("placed_at", "cooled_in", "heated_in", "examined_under", "sliced_with")


class TaskObject(Value):
    type: str
    roles: list[Role] = Field(min_length=1)
    confidence: float | None = None


class TaskGraph(Value):
    instruction: str
    room_type: str
    task_type: Literal[
        "pick_and_place_simple",
        "look_at_obj_in_light",
        "pick_cool_then_place_in_recep",
        "pick_heat_then_place_in_recep",
    ]
    objects: list[TaskObject]
    relations: list[tuple[str, str, str]] = Field(default_factory=list)
    sliced: bool = False
    # Set when the parser is not sure it understood the instruction (several tasks, no recognisable
    # task, not English, unknown objects); `messages` says why, in words a designer can act on.
    uncertain: bool = False
    messages: list[str] = Field(default_factory=list)
    provenance: Provenance | None = None

    @field_validator("relations")
    @classmethod
    def _known_relations(cls, relations: list[tuple[str, str, str]]) -> list[tuple[str, str, str]]:
        for _, rel, _ in relations:
            if rel not in RELATIONS:
                raise ValueError(f"unknown relation {rel!r}; expected one of {', '.join(RELATIONS)}")
        return relations

    def with_role(self, role: str) -> list[TaskObject]:
        return [o for o in self.objects if role in o.roles]

    @property
    def lamp_alone(self) -> bool:
        """A look-at task that names nothing to look at ("Turn on the lamp"): its key object is the lamp itself."""
        return self.task_type == "look_at_obj_in_light" and not self.relations and bool(self.with_role("key"))

    @property
    def anchor(self) -> TaskObject | None:
        found = self.with_role("anchor")
        return found[0] if found else None

    @property
    def target(self) -> str | None:
        """The object the task manipulates: the subject of every relation."""
        return self.relations[0][0] if self.relations else None
