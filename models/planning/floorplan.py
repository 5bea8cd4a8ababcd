"""Floorplans: rectangular rooms that share walls, one entrance from outside and interior doors.

`SlicingFloorplan` cuts one rectangle of the rooms' total area into the rooms: the rooms (in a seeded
order) are split into two groups of about equal area, the rectangle is cut across its longer side at
that area ratio, and each half is cut again for its group. Rooms therefore never overlap, cover the
house and share walls with their neighbours. Of several seeded orders and outlines it keeps the one
whose rooms are least elongated and in which every neighbour pair needed for connectivity shares
enough wall for a door; longer outlines, then small rooms made larger, only where no near-square
outline gives every room MIN_SIDE (`STAGES`). The entrance is cut into an outside wall of the hub (a
hallway, else the living room, kitchen...); interior doors follow a seeded spanning tree of the rooms
that share enough wall, grown from the entrance's room (so every room is reachable from the entrance);
windows go on outside walls only.
"""

from __future__ import annotations

import math
from functools import cache
import random
from dataclasses import dataclass
from typing import Protocol

from models.errors import InputError
from models.planning.shell import CORNER_MARGIN, WINDOW_MAX_HEIGHT, WINDOW_SILL, free_spans, snap
from models.values import Opening, Provenance, Room
from models.values.apartment import OUTSIDE, Doorway, Floorplan, HouseRoom
from models.world.catalogue import load_json

Rect = tuple[float, float, float, float]  # xmin, zmin, xmax, zmax in the house
HUB_ORDER = ("hallway", "living room", "kitchen", "dining room", "office", "garage", "laundry room", "bedroom",
             "bathroom")
HUB_TYPES = {"hallway", "living room"}
MIN_SIDE = 2.0  # no room narrower than this (metres)
ATTEMPTS = 40
# Tried in turn until one lays the rooms out: (the range of the outline's length over width, the least area of a
# room as a share of the mean room's). Near square at the rooms' own areas first; then longer outlines (a small room
# beside large ones is a strip under MIN_SIDE wide across a near-square house: a 10 m2 bathroom beside a 30 m2 living
# room is 1.6-2.0 m wide there, 2.5 m in a 10 x 4 m house); then small rooms grown to half the mean room's area (a
# 7 m2 bathroom among four rooms of 18-38 m2 is such a strip in any outline)
STAGES = (((1.0, 1.6), 0.0), ((1.6, 3.0), 0.0), ((1.0, 1.6), 0.5))
EPS = 1e-6


class FloorplanError(InputError):
    """The rooms cannot be laid out as asked (one line, for the CLI and the API)."""


class FloorplanMaker(Protocol):
    name: str

    def make(self, shells: list[Room], seed: int) -> Floorplan:
        """Lay out rooms of the shells' types, materials and (about) their areas; doors and windows added."""


@dataclass(frozen=True)
class WallPiece:
    """A stretch of one room's wall that faces a single neighbour (or OUTSIDE), in house coordinates."""

    room: str
    wall: str  # south / north / west / east of `room`
    other: str
    x0: float
    z0: float
    x1: float
    z1: float

    @property
    def length(self) -> float:
        return abs(self.x1 - self.x0) + abs(self.z1 - self.z0)


def _wall_lines(b: Rect) -> dict[str, tuple[str, float, float, float]]:
    """wall -> (axis it runs along, its fixed coordinate, lo, hi)."""
    x0, z0, x1, z1 = b
    return {"south": ("x", z0, x0, x1), "north": ("x", z1, x0, x1), "west": ("z", x0, z0, z1),
            "east": ("z", x1, z0, z1)}


OPPOSITE = {"south": "north", "north": "south", "west": "east", "east": "west"}


def wall_pieces(bounds: dict[str, Rect]) -> list[WallPiece]:
    """Every room's walls cut where a neighbour starts or ends: each piece faces one room or OUTSIDE."""
    lines = {rid: _wall_lines(b) for rid, b in bounds.items()}
    out = []
    for rid, walls in lines.items():
        for wall, (axis, c, lo, hi) in walls.items():
            shared = []
            for other, owalls in lines.items():
                _, oc, olo, ohi = owalls[OPPOSITE[wall]]
                if other != rid and abs(oc - c) < EPS and min(hi, ohi) - max(lo, olo) > EPS:
                    shared.append((max(lo, olo), min(hi, ohi), other))
            cursor, spans = lo, []
            for a, b, other in sorted(shared):
                if a - cursor > EPS:
                    spans.append((cursor, a, OUTSIDE))
                spans.append((a, b, other))
                cursor = b
            if hi - cursor > EPS:
                spans.append((cursor, hi, OUTSIDE))
            for a, b, other in spans:
                ends = (a, c, b, c) if axis == "x" else (c, a, c, b)
                out.append(WallPiece(rid, wall, other, *ends))
    return out


def _slice(rect: Rect, items: list[tuple[int, float]], out: dict[int, Rect]) -> None:
    """Guillotine cuts: two groups of about equal area, across the longer side, recursively."""
    if len(items) == 1:
        out[items[0][0]] = rect
        return
    total = sum(a for _, a in items)
    running = [sum(a for _, a in items[:k]) for k in range(1, len(items))]
    k = min(range(len(running)), key=lambda i: abs(running[i] - total / 2)) + 1
    share = running[k - 1] / total
    x0, z0, x1, z1 = rect
    if x1 - x0 >= z1 - z0:
        cut = min(max(snap(x0 + (x1 - x0) * share), x0 + 0.05), x1 - 0.05)
        halves = (x0, z0, cut, z1), (cut, z0, x1, z1)
    else:
        cut = min(max(snap(z0 + (z1 - z0) * share), z0 + 0.05), z1 - 0.05)
        halves = (x0, z0, x1, cut), (x0, cut, x1, z1)
    _slice(halves[0], items[:k], out)
    _slice(halves[1], items[k:], out)


def door_id(a: str, b: str) -> str:
    """ProcTHOR's naming: `door|2|3` between room|2 and room|3; `door|0|2` from outside into room|2."""
    num = {OUTSIDE: "0"}
    return "door|" + "|".join(sorted((num.get(r, r.split("|")[-1]) for r in (a, b)), key=int))


@cache
def _door_assets() -> dict[str, dict]:
    return {k: v for k, v in load_json("structure.json")["doors"].items() if "Double" not in k}


@cache
def _window_assets() -> dict[str, dict]:
    return load_json("structure.json")["windows"]


def _door_span() -> float:
    """The shortest wall piece any single door fits in, corners kept clear."""
    return max(h["width"] for h in _door_assets().values()) + 2 * CORNER_MARGIN


def _spanning_tree(start: str, edges: dict[tuple[str, str], WallPiece], types: dict[str, str],
                   rng: random.Random) -> list[WallPiece] | None:
    """A random spanning tree (Prim's order, doors to a hub preferred) from `start`; None if disconnected."""
    reached, tree = {start}, []
    while len(reached) < len(types):
        frontier = sorted((k, p) for k, p in edges.items() if (k[0] in reached) != (k[1] in reached))
        if not frontier:
            return None
        weights = [3.0 if types[k[0]] in HUB_TYPES or types[k[1]] in HUB_TYPES else 1.0 for k, _ in frontier]
        key, piece = rng.choices(frontier, weights=weights)[0]
        reached |= set(key)
        tree.append(piece)
    return tree


class SlicingFloorplan:
    name = "slicing"

    def make(self, shells: list[Room], seed: int) -> Floorplan:
        if not shells:
            raise FloorplanError("an apartment needs at least one room")
        rng = random.Random(seed)
        best = None
        for ratios, least in STAGES:
            for _ in range(ATTEMPTS):
                attempt = self._attempt(shells, rng, ratios, least)
                if attempt is not None and (best is None or attempt[0] < best[0]):
                    best = attempt
            if best is not None:
                break
        if best is None:
            raise FloorplanError(f"could not lay out {len(shells)} rooms at least {MIN_SIDE} m wide with a door "
                                 f"into each (at least {_door_span():.2f} m of shared wall)")
        _, bounds, tree, entrance = best
        return self._openings(shells, bounds, tree, entrance, rng, seed)

    def _attempt(self, shells: list[Room], rng: random.Random, ratios: tuple[float, float], least: float):
        """(score, bounds, door pieces, entrance piece) of one seeded slicing of an outline whose length over width is
        drawn from `ratios`, each room given at least `least` x the mean room's area; None if it fails."""
        order = list(range(len(shells)))
        rng.shuffle(order)
        floor = least * sum(s.width * s.depth for s in shells) / len(shells)
        areas = [(i, max(shells[i].width * shells[i].depth, floor)) for i in order]
        total = sum(a for _, a in areas)
        ratio = rng.uniform(*ratios)
        width = snap(math.sqrt(total * ratio))
        cut: dict[int, Rect] = {}
        _slice((0.0, 0.0, width, snap(total / width)), areas, cut)
        bounds = {f"room|{i + 1}": tuple(round(v, 3) for v in cut[i]) for i in range(len(shells))}
        sides = [min(b[2] - b[0], b[3] - b[1]) for b in bounds.values()]
        if min(sides) < MIN_SIDE:
            return None
        types = {f"room|{i + 1}": s.type for i, s in enumerate(shells)}
        pieces = wall_pieces(bounds)
        span = _door_span()
        outside = [p for p in pieces if p.other == OUTSIDE and p.length >= span]
        if not outside:
            return None
        hub = min({p.room for p in outside}, key=lambda r: (HUB_ORDER.index(types[r]), r))
        edges = {tuple(sorted((p.room, p.other))): p for p in pieces
                 if p.other != OUTSIDE and p.room < p.other and p.length >= span}
        tree = _spanning_tree(hub, edges, types, rng)
        if tree is None:
            return None
        aspect = max(max(b[2] - b[0], b[3] - b[1]) / min(b[2] - b[0], b[3] - b[1]) for b in bounds.values())
        entrance = rng.choice([p for p in outside if p.room == hub])
        return aspect, bounds, tree, entrance

    def _openings(self, shells: list[Room], bounds: dict[str, Rect], tree: list[WallPiece], entrance: WallPiece,
                  rng: random.Random, seed: int) -> Floorplan:
        assets = _door_assets()
        openings: dict[str, dict[str, list[Opening]]] = {rid: {"doors": [], "windows": []} for rid in bounds}
        doors = []
        for piece in [entrance] + tree:
            name = rng.choice(sorted(assets))
            hole = assets[name]
            lo = CORNER_MARGIN + hole["width"] / 2
            centre = min(max(snap(rng.uniform(lo, piece.length - lo)), lo), piece.length - lo)
            rooms = (piece.room, piece.other)
            doors.append(Doorway(id=door_id(*rooms), rooms=rooms, x0=piece.x0, z0=piece.z0, x1=piece.x1, z1=piece.z1,
                                 center=round(centre, 3), width=hole["width"], asset_id=name))
            for rid in rooms:
                if rid != OUTSIDE:
                    openings[rid]["doors"].append(self._local(bounds[rid], piece, centre, hole, name, 0.0))
        pieces = wall_pieces(bounds)
        for rid in bounds:
            self._windows(rid, bounds[rid], pieces, doors, openings[rid]["windows"], rng)
        rooms = []
        for i, shell in enumerate(shells):
            rid = f"room|{i + 1}"
            x0, z0, x1, z1 = bounds[rid]
            room = Room(**{**shell.model_dump(), "width": round(x1 - x0, 3), "depth": round(z1 - z0, 3),
                           **openings[rid], "crossed": len(openings[rid]["doors"]) > 1 or None})
            rooms.append(HouseRoom(id=rid, room=room, x=x0, z=z0))
        return Floorplan(rooms=rooms, doors=doors, entrance=doors[0].id,
                         provenance=Provenance(stage="floorplan", method=self.name, seed=seed))

    @staticmethod
    def _local(b: Rect, piece: WallPiece, centre: float, hole: dict, asset: str, sill: float) -> Opening:
        """An opening at `centre` along `piece`, as the room with bounds `b` sees it on its own wall."""
        horizontal = piece.z0 == piece.z1
        if horizontal:
            wall = "south" if abs(piece.z0 - b[1]) < EPS else "north"
            local = piece.x0 + centre - b[0]
        else:
            wall = "west" if abs(piece.x0 - b[0]) < EPS else "east"
            local = piece.z0 + centre - b[1]
        return Opening(wall=wall, center=round(local, 3), width=hole["width"], asset_id=asset,
                       height=hole["height"], sill=sill)

    def _windows(self, rid: str, b: Rect, pieces: list[WallPiece], doors: list[Doorway], out: list[Opening],
                 rng: random.Random) -> None:
        """0-2 windows (0-1 in small rooms) on the room's outside walls, clear of doors and corners."""
        windows = _window_assets()
        names = sorted(k for k, h in windows.items() if h["height"] <= WINDOW_MAX_HEIGHT)
        outside = [p for p in pieces if p.room == rid and p.other == OUTSIDE]
        count = rng.choice((0, 1, 1, 2)) if (b[2] - b[0]) * (b[3] - b[1]) > 9 else rng.choice((0, 1))
        taken: dict[WallPiece, list[tuple[float, float]]] = {p: [] for p in outside}
        for d in doors:
            for p in outside:
                if (d.x0, d.z0, d.x1, d.z1) == (p.x0, p.z0, p.x1, p.z1):
                    taken[p].append((d.center - d.width / 2, d.center + d.width / 2))
        for _ in range(count):
            name = rng.choice(names)
            hole = windows[name]
            for piece in rng.sample(outside, len(outside)):
                spans = free_spans(piece.length, taken[piece], hole["width"])
                if spans:
                    lo, hi = rng.choice(spans)
                    centre = min(max(snap(rng.uniform(lo, hi)), lo), hi)
                    taken[piece].append((centre - hole["width"] / 2, centre + hole["width"] / 2))
                    out.append(self._local(b, piece, centre, hole, name, WINDOW_SILL))
                    break
