"""Where a robot of 0.2 m radius can go: an occupancy grid, the free space reachable from the door,
and whether it can stand in front of an object.

A cell is free when its centre is at least the robot's radius from every object footprint and from
every wall. The robot starts in the doorway (the door's width, up to 0.6 m into the room). Reachability
is answered for all targets at once by labelling the connected free space (4-neighbour), which is the
question A* answers (does a path exist) without searching once per target.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import shapely
from shapely.geometry import Polygon

from models.compiled import compiled
from models.energy.weights import ACCESS_DEPTH, NAV_CELL, ROBOT_RADIUS
from models.geometry import Footprint
from models.values import Room

DOOR_DEPTH = 0.6
GRIDS_KEPT = 64  # rooms whose cell centres are kept (`_cell_centres`)


@dataclass(frozen=True)
class Grid:
    width: float
    depth: float
    cell: float = NAV_CELL

    @property
    def xs(self) -> np.ndarray:
        return np.arange(self.cell / 2, self.width, self.cell)

    @property
    def zs(self) -> np.ndarray:
        return np.arange(self.cell / 2, self.depth, self.cell)

    def mesh(self) -> tuple[np.ndarray, np.ndarray]:
        return np.meshgrid(self.xs, self.zs, indexing="ij")


def door_boxes(room: Room) -> list[tuple[float, float, float, float]]:
    """Where the robot may start: inside each doorway, as boxes (xmin, zmin, xmax, zmax)."""
    out = []
    for d in room.doors:
        lo, hi = d.center - d.width / 2, d.center + d.width / 2
        out.append({"south": (lo, 0, hi, DOOR_DEPTH), "north": (lo, room.depth - DOOR_DEPTH, hi, room.depth),
                    "west": (0, lo, DOOR_DEPTH, hi), "east": (room.width - DOOR_DEPTH, lo, room.width, hi)}[d.wall])
    return out


@lru_cache(maxsize=GRIDS_KEPT)
def _cell_centres(grid: Grid) -> np.ndarray:
    """The grid's cell centres as shapely points, made once per grid: they cost more than the tests against them
    (the studio's checks and the metrics ask about the same room again and again)."""
    centres = shapely.points(*grid.mesh())
    centres.flags.writeable = False
    return centres


def blocked_by_polygons(grid: Grid, polygons: list[Polygon], radius: float = ROBOT_RADIUS) -> np.ndarray:
    """Exact: cells whose centre is within `radius` of a polygon or of a wall."""
    gx, gz = grid.mesh()
    blocked = (gx < radius) | (gz < radius) | (gx > grid.width - radius) | (gz > grid.depth - radius)
    centres = _cell_centres(grid) if polygons else None
    for poly in polygons:
        blocked |= shapely.dwithin(poly, centres, radius)
    return blocked


def blocked_by_boxes(grid: Grid, boxes: np.ndarray, radius: float = ROBOT_RADIUS) -> np.ndarray:
    """The same for axis-aligned boxes (M, 4), each evaluated only on the cells near it."""
    gx, gz = grid.mesh()
    blocked = (gx < radius) | (gz < radius) | (gx > grid.width - radius) | (gz > grid.depth - radius)
    for b in np.asarray(boxes, float).reshape(-1, 4):
        _mark_near(blocked, gx[:, 0], gz[0], b, b[None], radius, grid.width, grid.depth, False)
    return blocked


def in_box_mask(grid: Grid, box) -> np.ndarray:
    gx, gz = grid.mesh()
    return (gx >= box[0]) & (gx <= box[2]) & (gz >= box[1]) & (gz <= box[3])


def door_masks(grid: Grid, room: Room) -> list[np.ndarray]:
    """Each door's cells (inside its doorway), in the room's order of doors."""
    return [in_box_mask(grid, box) for box in door_boxes(room)]


def door_cells(grid: Grid, room: Room) -> np.ndarray:
    """The cells the robot may start from (inside a doorway)."""
    start = np.zeros(grid.mesh()[0].shape, bool)
    for door in door_masks(grid, room):
        start |= door
    return start


def doors_joined(room: Room, boxes: np.ndarray) -> bool:
    """Whether the robot can walk from each of the room's doors to every other past the objects' boxes (M, 4): a
    room it crosses on its way to the next one."""
    grid = Grid(room.width, room.depth)
    doors = door_masks(grid, room)
    if len(doors) < 2:
        return True
    reach = reachable_from(blocked_by_boxes(grid, boxes), doors[0])  # free cells only, so a blocked door is apart
    return all((reach & d).any() for d in doors[1:])


def reachable_space(grid: Grid, blocked: np.ndarray, room: Room) -> np.ndarray:
    """Free cells connected to a free cell of some doorway."""
    return reachable_from(blocked, door_cells(grid, room))


def reachable_from(blocked: np.ndarray, start: np.ndarray) -> np.ndarray:
    """Free cells connected (4-neighbour) to a free cell of `start` (both (nx, nz) masks)."""
    return _flood(np.ascontiguousarray(blocked, np.bool_), np.ascontiguousarray(start, np.bool_))


@compiled
def _flood(blocked, start):
    """`reachable_from` as a flood fill from the free start cells: the placers label the free space thousands of
    times per plan, and labelling every component (scipy.ndimage.label) costs more than walking one."""
    nx, nz = blocked.shape
    out = np.zeros((nx, nz), np.bool_)
    stack = np.empty(nx * nz, np.int64)
    top = 0
    for i in range(nx):
        for j in range(nz):
            if start[i, j] and not blocked[i, j]:
                out[i, j] = True
                stack[top] = i * nz + j
                top += 1
    while top:
        top -= 1
        i, j = stack[top] // nz, stack[top] % nz
        for a, b in ((i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)):
            if 0 <= a < nx and 0 <= b < nz and not blocked[a, b] and not out[a, b]:
                out[a, b] = True
                stack[top] = a * nz + b
                top += 1
    return out


@compiled
def _mark_near(blocked, xs, zs, b, boxes, radius, width, depth, relabel):
    """In the cells of centres `xs` x `zs` near box b (those a robot of `radius` near it can touch, with a cell's
    width of margin): with `relabel`, set each to whether a wall or one of `boxes` (M, 4) lies within `radius` of
    its centre; without, mark those within `radius` of one of `boxes`."""
    margin = radius + (xs[1] - xs[0] if len(xs) > 1 else 0.0)
    r0, r1 = np.searchsorted(xs, b[0] - margin), np.searchsorted(xs, b[2] + margin, side="right")
    c0, c1 = np.searchsorted(zs, b[1] - margin), np.searchsorted(zs, b[3] + margin, side="right")
    limit = radius * radius + 1e-12
    for i in range(r0, r1):
        x = xs[i]
        for j in range(c0, c1):
            z = zs[j]
            near = relabel and (x < radius or z < radius or x > width - radius or z > depth - radius)
            for m in range(boxes.shape[0]):
                if near:
                    break
                dx = max(0.0, max(boxes[m, 0] - x, x - boxes[m, 2]))
                dz = max(0.0, max(boxes[m, 1] - z, z - boxes[m, 3]))
                near = dx * dx + dz * dz <= limit
            if relabel or near:
                blocked[i, j] = near


def blocked_with(mesh: tuple[np.ndarray, np.ndarray], blocked: np.ndarray, b: np.ndarray,
                 radius: float = ROBOT_RADIUS) -> np.ndarray:
    """`blocked | blocked_by_boxes(grid, [b])` for a grid whose walls `blocked` already holds, evaluated only
    on the cells near the box b (farther cells are more than the robot's radius away); `mesh`: grid.mesh()."""
    out, b = blocked.copy(), np.asarray(b, float)
    _mark_near(out, mesh[0][:, 0], mesh[1][0], b, b[None], radius, 0.0, 0.0, False)
    return out


def blocked_without(grid: Grid, mesh: tuple[np.ndarray, np.ndarray], blocked: np.ndarray, b: np.ndarray,
                    others: np.ndarray, radius: float = ROBOT_RADIUS) -> np.ndarray:
    """`blocked_by_boxes(grid, others)` for a grid `blocked` that also holds box b: only the cells near b
    (those b can block) are labelled again, by the walls and the `others` (M, 4) that reach them."""
    out = blocked.copy()
    _mark_near(out, mesh[0][:, 0], mesh[1][0], np.asarray(b, float), np.asarray(others, float).reshape(-1, 4),
               radius, grid.width, grid.depth, True)
    return out


def access_strip(f: Footprint, depth: float = ACCESS_DEPTH) -> Footprint:
    """The floor in front of an object where the robot stands to use it."""
    return f.front_zone(depth)


def strip_mask(grid: Grid, f: Footprint) -> np.ndarray:
    """The cells of the object's access strip."""
    gx, gz = grid.mesh()
    return shapely.contains_xy(access_strip(f).polygon(), gx, gz)


def can_reach(grid: Grid, reachable: np.ndarray, f: Footprint) -> bool:
    return bool((strip_mask(grid, f) & reachable).any())

