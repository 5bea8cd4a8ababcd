"""The floors and doorways of an exported house (ProcTHOR JSON), for the symbolic robot.

In a house of several rooms the robot walks on each room's floor, away from its walls, and from room to
room only through the doorways between rooms (a door whose room0 and room1 differ); the entrance, a
door to the outside, is no way anywhere. A room's floor is its `floorPolygon`; a doorway is the stretch
of its `wall0` that the door's `holePolygon` cuts (offsets from the wall's first point).
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from pydantic import BaseModel, ConfigDict

from models.energy import navigation as nav
from models.energy.house_navigation import passage_mask


class Passage(BaseModel):
    """A doorway between two rooms: the hole's stretch from (x0, z0) to (x1, z1), house frame."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    x0: float
    z0: float
    x1: float
    z1: float


def floors(house: dict) -> dict[str, list[tuple[float, float]]]:
    """room id -> its floor polygon (x, z)."""
    return {r["id"]: [(v["x"], v["z"]) for v in r["floorPolygon"]] for r in house.get("rooms", [])}


def passages(house: dict) -> list[Passage]:
    walls = {w["id"]: w["polygon"] for w in house.get("walls", [])}
    out = []
    for door in house.get("doors", []):
        if door["room0"] == door["room1"] or door["wall0"] not in walls:
            continue
        a, b = walls[door["wall0"]][:2]
        length = math.hypot(b["x"] - a["x"], b["z"] - a["z"]) or 1.0
        ux, uz = (b["x"] - a["x"]) / length, (b["z"] - a["z"]) / length
        lo, hi = door["holePolygon"][0]["x"], door["holePolygon"][1]["x"]
        out.append(Passage(x0=a["x"] + ux * lo, z0=a["z"] + uz * lo, x1=a["x"] + ux * hi, z1=a["z"] + uz * hi))
    return out


def room_cells(grid: nav.Grid, origin: tuple[float, float], rooms: dict[str, list[tuple[float, float]]]) -> np.ndarray:
    """Per cell, the index (in `rooms` order) of the room whose floor holds its centre; -1 for none."""
    gx, gz = grid.mesh()
    xs, zs = gx + origin[0], gz + origin[1]
    out = np.full(gx.shape, -1, dtype=np.int16)
    for k, polygon in enumerate(rooms.values()):
        out[shapely.contains_xy(shapely.Polygon(polygon), xs, zs)] = k
    return out


def walkable(grid: nav.Grid, origin: tuple[float, float], rooms: dict[str, list[tuple[float, float]]],
             doorways: list[Passage], radius: float) -> np.ndarray:
    """Cells at least `radius` inside some room's floor, or in a doorway between rooms."""
    gx, gz = grid.mesh()
    xs, zs = gx + origin[0], gz + origin[1]
    free = np.zeros(gx.shape, dtype=bool)
    for polygon in rooms.values():
        free |= shapely.contains_xy(shapely.Polygon(polygon).buffer(-radius, join_style="mitre"), xs, zs)
    for p in doorways:
        free |= passage_mask(grid, p.x0 - origin[0], p.z0 - origin[1], p.x1 - origin[0], p.z1 - origin[1], radius)
    return free
