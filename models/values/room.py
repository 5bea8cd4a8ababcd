"""The room shell shared by RoomPlan and ConstraintPlan (interfaces.md, "Constraint plan": room)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from models.values.common import Value

Wall = Literal["south", "north", "west", "east"]


class Opening(Value):
    """A door or window: `center` is measured along its wall from the wall's lower-coordinate end."""

    wall: Wall
    center: float
    width: float = Field(gt=0)
    asset_id: str | None = None
    height: float | None = None
    sill: float | None = None


class Room(Value):
    type: str
    width: float = Field(gt=0, le=50)
    depth: float = Field(gt=0, le=50)
    doors: list[Opening] = Field(default_factory=list)
    windows: list[Opening] = Field(default_factory=list)
    wall_height: float | None = None
    floor_material: str | None = None
    wall_material: str | None = None
    # True: a room with several doors the robot may walk between (an apartment's; a single room's, which it enters by
    # one): Plan2Place keeps them joined
    crossed: bool | None = None

    def wall_length(self, wall: str) -> float:
        return self.width if wall in ("south", "north") else self.depth

    @model_validator(mode="after")
    def _openings_fit(self) -> Room:
        for kind, items in (("door", self.doors), ("window", self.windows)):
            for o in items:
                length = self.wall_length(o.wall)
                if o.center - o.width / 2 < -1e-6 or o.center + o.width / 2 > length + 1e-6:
                    raise ValueError(f"{kind} on the {o.wall} wall (centre {o.center}, width {o.width}) "
                                     f"does not fit the wall of length {length}")
        return self
