"""Layout: a placer's answer (interfaces.md, "Layout")."""

from __future__ import annotations

from pydantic import Field

from models.values.common import Provenance, Size, Value


class Placement(Value):
    id: str
    type: str
    x: float
    z: float
    rotation: float
    size: Size


class Unplaced(Value):
    id: str
    reason: str


class Timing(Value):
    total_s: float
    per_object_s: float


class Layout(Value):
    plan_id: str
    solver: str
    seed: int
    placements: list[Placement] = Field(default_factory=list)
    unplaced: list[Unplaced] = Field(default_factory=list)
    warnings: list[str] = Field(default_factory=list)
    timing: Timing
    provenance: Provenance | None = None

    def placement(self, object_id: str) -> Placement | None:
        return next((p for p in self.placements if p.id == object_id), None)
