"""The room's walls as solid boxes around their door and window openings (Unity coordinates, y up).

Shared by the GLB export and the studio's 3D view.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from models.values import Room

WALL_THICKNESS = 0.1
OUTWARD = {"south": (0, -1), "north": (0, 1), "west": (-1, 0), "east": (1, 0)}


def wall_segments(width: float, depth: float) -> dict[str, tuple[float, float, float, float]]:
    """Each wall from its lower-coordinate end to the other, as (x0, z0, x1, z1)."""
    return {"south": (0, 0, width, 0), "north": (0, depth, width, depth),
            "west": (0, 0, 0, depth), "east": (width, 0, width, depth)}


@dataclass(frozen=True)
class WallBox:
    name: str
    extents: tuple[float, float, float]  # x, y, z sizes
    centre: tuple[float, float, float]


def wall_boxes(room: Room) -> list[WallBox]:
    height = room.wall_height or 2.6
    out = []
    for wall, (x0, z0, x1, z1) in wall_segments(room.width, room.depth).items():
        length = room.wall_length(wall)
        holes = sorted((o.center - o.width / 2, o.center + o.width / 2, o.sill or 0.0, (o.sill or 0.0) + (o.height or 2.0))
                       for o in room.doors + room.windows if o.wall == wall)
        spans, cursor = [], 0.0
        for lo, hi, bottom, top in holes:
            spans.append((cursor, lo, 0.0, height))
            if bottom > 0:
                spans.append((lo, hi, 0.0, bottom))
            spans.append((lo, hi, top, height))
            cursor = hi
        spans.append((cursor, length, 0.0, height))
        along = np.array([x1 - x0, z1 - z0]) / length
        ox, oz = OUTWARD[wall]
        for k, (a, b, y0, y1) in enumerate(spans):
            if b - a < 1e-3 or y1 - y0 < 1e-3:
                continue
            mid = (a + b) / 2
            centre = (x0 + along[0] * mid + ox * WALL_THICKNESS / 2, (y0 + y1) / 2,
                      z0 + along[1] * mid + oz * WALL_THICKNESS / 2)
            extents = (b - a, y1 - y0, WALL_THICKNESS) if wall in ("south", "north") else \
                (WALL_THICKNESS, y1 - y0, b - a)
            out.append(WallBox(f"wall-{wall}-{k}", extents, centre))
    return out
