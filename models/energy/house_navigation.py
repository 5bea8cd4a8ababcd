"""Navigation across an apartment: the robot walks from its start by the entrance through the doors.

One occupancy grid over the whole house (the single-room grid of models.energy.navigation, 5 cm cells,
a robot of 0.2 m radius): a cell is free when it is inside some room, at least the robot's radius from
that room's walls, or in a doorway cut through a wall; and clear of every object. A task object is
reached when a free cell of its access strip is connected to the robot's start. The path is the
shortest 4-neighbour walk over the grid (breadth first), visiting the task objects one after another.
Objects are taken as their axis-aligned boxes (exact for the placers' quarter turns).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage
from scipy.sparse import coo_matrix, csr_matrix
from scipy.sparse.csgraph import breadth_first_order

from models.energy import navigation as nav
from models.energy.weights import ROBOT_RADIUS
from models.geometry import Footprint, boxes
from models.values.apartment import Doorway, Floorplan, RobotPath


def house_grid(floorplan: Floorplan) -> nav.Grid:
    width, depth = floorplan.size
    return nav.Grid(width, depth)


def passage_mask(grid: nav.Grid, x0: float, z0: float, x1: float, z1: float, radius: float) -> np.ndarray:
    """Cells through a hole from (x0, z0) to (x1, z1) in a wall along x or z: across the wall (both sides),
    the hole's width less the radius at each end."""
    gx, gz = grid.mesh()
    reach = radius + grid.cell
    if z0 == z1:  # a wall along x at z0
        return (gx >= min(x0, x1) + radius) & (gx <= max(x0, x1) - radius) & (np.abs(gz - z0) <= reach)
    return (gz >= min(z0, z1) + radius) & (gz <= max(z0, z1) - radius) & (np.abs(gx - x0) <= reach)


def _door_passage(grid: nav.Grid, door: Doorway, radius: float) -> np.ndarray:
    if door.z0 == door.z1:
        lo, hi = door.x0 + door.center - door.width / 2, door.x0 + door.center + door.width / 2
        return passage_mask(grid, lo, door.z0, hi, door.z0, radius)
    lo, hi = door.z0 + door.center - door.width / 2, door.z0 + door.center + door.width / 2
    return passage_mask(grid, door.x0, lo, door.x0, hi, radius)


def house_blocked(grid: nav.Grid, floorplan: Floorplan, objects: list[Footprint],
                  radius: float = ROBOT_RADIUS) -> np.ndarray:
    gx, gz = grid.mesh()
    free = np.zeros(gx.shape, dtype=bool)
    for hr in floorplan.rooms:
        x0, z0, x1, z1 = hr.bounds
        free |= (gx >= x0 + radius) & (gx <= x1 - radius) & (gz >= z0 + radius) & (gz <= z1 - radius)
    for door in floorplan.doors:
        free |= _door_passage(grid, door, radius)
    found = boxes([f.x for f in objects], [f.z for f in objects], [f.width for f in objects],
                  [f.depth for f in objects], [f.rotation for f in objects]).reshape(-1, 4)
    return ~free | nav.blocked_by_boxes(grid, found, radius)


def _start_cells(grid: nav.Grid, blocked: np.ndarray, start: tuple[float, float]) -> np.ndarray:
    """The free cells within 0.3 m of the start (it may stand on a blocked cell's edge)."""
    gx, gz = grid.mesh()
    return ~blocked & ((gx - start[0]) ** 2 + (gz - start[1]) ** 2 <= 0.3 ** 2)


def reachable_from(grid: nav.Grid, blocked: np.ndarray, start: tuple[float, float]) -> np.ndarray:
    labels, _ = ndimage.label(~blocked)
    ids = np.unique(labels[_start_cells(grid, blocked, start)])
    return np.isin(labels, ids[ids > 0])


def _grid_graph(free: np.ndarray) -> csr_matrix:
    """The free cells as an undirected graph of 4-neighbours (cell index = i * columns + k)."""
    idx = np.arange(free.size).reshape(free.shape)
    down, right = free[:-1] & free[1:], free[:, :-1] & free[:, 1:]
    rows = np.concatenate([idx[:-1][down], idx[:, :-1][right]])
    cols = np.concatenate([idx[1:][down], idx[:, 1:][right]])
    return coo_matrix((np.ones(len(rows), dtype=np.int8), (rows, cols)), shape=(free.size, free.size)).tocsr()


def _walk(graph: csr_matrix, start: int, goal: np.ndarray) -> list[int] | None:
    """The shortest walk from cell `start` to the nearest cell of `goal` (flat mask), breadth first."""
    order, parents = breadth_first_order(graph, start, directed=False, return_predecessors=True)
    hits = order[goal[order]]
    if not len(hits):
        return None
    cells = [int(hits[0])]
    while cells[-1] != start:
        cells.append(int(parents[cells[-1]]))
    return cells[::-1]


def _corners(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Only the points where the walk turns."""
    out = points[:2]
    for p in points[2:]:
        a, b = out[-2], out[-1]
        if (b[0] - a[0]) * (p[1] - b[1]) == (b[1] - a[1]) * (p[0] - b[0]):
            out[-1] = p
        else:
            out.append(p)
    return out


@dataclass(frozen=True)
class HouseNavigation:
    key_nav: float | None
    e_nav: float
    path: RobotPath


def house_navigation(floorplan: Floorplan, objects: dict[str, Footprint], targets: list[str],
                     start: tuple[float, float]) -> HouseNavigation:
    """Key_NAV and E_nav over `targets` (task object ids in visiting order; an unplaced one is missing from
    `objects` and unreachable), and the robot's path from `start` to each reached one in turn."""
    grid = house_grid(floorplan)
    blocked = house_blocked(grid, floorplan, list(objects.values()))
    reachable = reachable_from(grid, blocked, start)
    gx, gz = grid.mesh()
    graph = _grid_graph(reachable)
    near = np.flatnonzero((_start_cells(grid, blocked, start) & reachable).ravel())
    gap = (gx.ravel()[near] - start[0]) ** 2 + (gz.ravel()[near] - start[1]) ** 2
    here = int(near[np.argmin(gap)]) if len(near) else None
    points, visits, missed = [start], [], []
    for oid in targets:
        f = objects.get(oid)
        cells = None
        if f is not None and here is not None:
            cells = _walk(graph, here, (reachable & nav.strip_mask(grid, f)).ravel())
        if cells is None:
            missed.append(oid)
            continue
        points += [(round(float(gx.flat[c]), 3), round(float(gz.flat[c]), 3)) for c in cells]
        visits.append(oid)
        here = cells[-1]
    key_nav = len(visits) / len(targets) if targets else None
    return HouseNavigation(key_nav=key_nav, e_nav=(1 - key_nav) ** 2 if targets else 0.0,
                           path=RobotPath(points=_corners(points), visits=visits, unreachable=missed))
