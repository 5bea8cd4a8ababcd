"""The room shell: size, doors, windows and materials for a room type, from ProcTHOR's databases."""

from __future__ import annotations

import random

from models.values import Opening, Room
from models.world.catalogue import load_json
from models.world.rooms import ROOM_SPECS

WALLS = ("south", "north", "west", "east")
CORNER_MARGIN = 0.3
WALL_HEIGHT = 2.6
WINDOW_SILL = 0.8  # window holes start this high above the floor
WINDOW_MAX_HEIGHT = WALL_HEIGHT - WINDOW_SILL - 0.2


def snap(v: float, step: float = 0.05) -> float:
    return round(round(v / step) * step, 3)


def free_spans(length: float, taken: list[tuple[float, float]], need: float) -> list[tuple[float, float]]:
    """Intervals of centre positions where an opening of width `need` fits between the taken ones."""
    spans, start = [], CORNER_MARGIN
    for lo, hi in sorted(taken) + [(length - CORNER_MARGIN, length)]:
        if lo - start >= need:
            spans.append((start + need / 2, lo - need / 2))
        start = max(start, hi + 0.1)
    return spans


def _place_opening(rng: random.Random, room_sides: dict[str, float], taken: dict[str, list], width: float,
                   walls: list[str]) -> tuple[str, float] | None:
    for wall in walls:
        spans = free_spans(room_sides[wall], taken[wall], width)
        if spans:
            lo, hi = rng.choice(spans)
            centre = snap(rng.uniform(lo, hi)) if hi > lo else snap(lo)
            centre = min(max(centre, CORNER_MARGIN + width / 2), room_sides[wall] - CORNER_MARGIN - width / 2)
            taken[wall].append((centre - width / 2, centre + width / 2))
            return wall, centre
    return None


def make_room(room_type: str, rng: random.Random, min_area: float = 0.0, size_scale: float = 1.0,
              n_doors: int | None = None, n_windows: int | None = None) -> Room:
    """A rectangular room of the type's size range, with 1-2 doors and 0-2 windows on distinct spans."""
    spec = ROOM_SPECS[room_type]
    structure = load_json("structure.json")
    lo, hi = spec.min_side * size_scale, spec.max_side * size_scale
    width, depth = snap(rng.uniform(lo, hi)), snap(rng.uniform(lo, hi))
    while width * depth < min_area:
        width, depth = snap(width * 1.1), snap(depth * 1.1)
    sides = {"south": width, "north": width, "west": depth, "east": depth}
    taken: dict[str, list] = {w: [] for w in WALLS}

    doors = []
    single = sorted(k for k in structure["doors"] if "Double" not in k)
    for _ in range(n_doors if n_doors is not None else rng.choice((1, 1, 1, 2))):
        asset = rng.choice(single)
        hole = structure["doors"][asset]
        walls = rng.sample(WALLS, 4)
        spot = _place_opening(rng, sides, taken, hole["width"], walls)
        if spot:
            doors.append(Opening(wall=spot[0], center=spot[1], width=hole["width"], asset_id=asset,
                                 height=hole["height"], sill=0.0))
    windows = []
    door_walls = {d.wall for d in doors}
    for _ in range(n_windows if n_windows is not None else rng.choice((0, 1, 1, 2))):
        asset = rng.choice(sorted(k for k, h in structure["windows"].items() if h["height"] <= WINDOW_MAX_HEIGHT))
        hole = structure["windows"][asset]
        walls = [w for w in rng.sample(WALLS, 4) if w not in door_walls] + sorted(door_walls)
        spot = _place_opening(rng, sides, taken, hole["width"], walls)
        if spot:
            windows.append(Opening(wall=spot[0], center=spot[1], width=hole["width"], asset_id=asset,
                                   height=hole["height"], sill=WINDOW_SILL))
    return Room(type=room_type, width=width, depth=depth, doors=doors, windows=windows, wall_height=WALL_HEIGHT,
                floor_material=rng.choice(structure["floor_materials"]),
                wall_material=rng.choice(structure["wall_materials"]))
