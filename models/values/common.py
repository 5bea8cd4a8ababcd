"""Small shared value types."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field


class Value(BaseModel):
    """Base of every pipeline value: immutable, and strict about unknown fields only where we read user input."""

    model_config = ConfigDict(frozen=True, extra="ignore")


class Size(Value):
    """An object's bounding box in metres: x = width, y = height, z = depth (front faces +z at rotation 0)."""

    x: float = Field(gt=0)
    y: float = Field(gt=0)
    z: float = Field(gt=0)


class Provenance(Value):
    """Where a value came from, so that any file can be reproduced."""

    stage: str
    method: str
    seed: int | None = None
    versions: dict[str, str] = Field(default_factory=dict)
