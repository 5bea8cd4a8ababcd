"""Footprint geometry on the floor plane (x, z) with the rotation convention of interfaces.md.

A footprint is an object's width x depth rectangle centred at (x, z), turned by `rotation` degrees about
+y: its front is (sin r, cos r) and its right is (cos r, -sin r). The scalar functions are exact for any
rotation (shapely); the `*_many` functions are vectorised with numpy over axis-aligned boxes, exact for
rotations that are multiples of 90 degrees (the placers' case) and conservative otherwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from shapely.geometry import Polygon, box

from models.compiled import compiled


def front(rotation: float) -> tuple[float, float]:
    r = math.radians(rotation)
    return math.sin(r), math.cos(r)


def right(rotation: float) -> tuple[float, float]:
    r = math.radians(rotation)
    return math.cos(r), -math.sin(r)


def half_extents(width, depth, rotation):
    """Half-sizes along x and z of the axis-aligned box around a turned rectangle (numpy-friendly)."""
    r = np.radians(rotation)
    c, s = np.abs(np.cos(r)), np.abs(np.sin(r))
    return (width * c + depth * s) / 2, (width * s + depth * c) / 2


@dataclass(frozen=True)
class Footprint:
    x: float
    z: float
    width: float
    depth: float
    rotation: float = 0.0

    def corners(self) -> list[tuple[float, float]]:
        """Corners counter-clockwise from back-left, in world (x, z)."""
        fx, fz = front(self.rotation)
        rx, rz = right(self.rotation)
        hw, hd = self.width / 2, self.depth / 2
        return [(self.x + lx * rx + lz * fx, self.z + lx * rz + lz * fz)
                for lx, lz in ((-hw, -hd), (hw, -hd), (hw, hd), (-hw, hd))]

    def polygon(self) -> Polygon:
        return Polygon(self.corners())

    def front_zone(self, clearance: float, widen: float = 0.0) -> Footprint:
        """The rectangle of depth `clearance` in front of the object (the space needed to use it)."""
        fx, fz = front(self.rotation)
        offset = self.depth / 2 + clearance / 2
        return Footprint(self.x + fx * offset, self.z + fz * offset, self.width + widen, clearance, self.rotation)


# GEOS (3.14) can return a whole polygon as the "intersection" of two rotated rectangles that only
# share an edge; snapping to a nanometre grid makes the overlay robust at no cost in accuracy.
SNAP_GRID = 1e-9


def intersection_area(p, q) -> float:
    """Area shared by two shapely polygons, robust to touching edges."""
    return p.intersection(q, grid_size=SNAP_GRID).area


def overlap_area(a: Footprint, b: Footprint) -> float:
    return intersection_area(a.polygon(), b.polygon())


def gap(a: Footprint, b: Footprint) -> float:
    """Shortest distance between two footprints, 0 when they touch or overlap."""
    return a.polygon().distance(b.polygon())


def outside_area(a: Footprint, width: float, depth: float) -> float:
    """Area of the footprint that lies outside the room [0, width] x [0, depth]."""
    poly = a.polygon()
    return poly.area - intersection_area(poly, box(0, 0, width, depth))


def inside_room(a: Footprint, width: float, depth: float, tol: float = 1e-6) -> bool:
    xs, zs = zip(*a.corners())
    return min(xs) >= -tol and min(zs) >= -tol and max(xs) <= width + tol and max(zs) <= depth + tol


def wall_clearance(a: Footprint, width: float, depth: float) -> float:
    """Smallest distance from the footprint to any of the four walls (negative if it crosses one)."""
    xs, zs = zip(*a.corners())
    return min(min(xs), min(zs), width - max(xs), depth - max(zs))


# ---- vectorised, axis-aligned -------------------------------------------------------------------

def boxes(x, z, width, depth, rotation) -> np.ndarray:
    """(N, 4) array of axis-aligned boxes [xmin, zmin, xmax, zmax]."""
    ex, ez = half_extents(np.asarray(width, float), np.asarray(depth, float), np.asarray(rotation, float))
    x, z = np.asarray(x, float), np.asarray(z, float)
    return np.stack(np.broadcast_arrays(x - ex, z - ez, x + ex, z + ez), axis=-1)


@lru_cache(maxsize=None)
def turn(rotation: float) -> tuple[float, float]:
    """sin and cos of one rotation in degrees, computed as numpy computes them for arrays (so the one-pose
    shortcuts below equal the array functions to the bit)."""
    r = np.radians(np.array([rotation]))
    return float(np.sin(r)[0]), float(np.cos(r)[0])


def one_box(x: float, z: float, width: float, depth: float, rotation: float) -> np.ndarray:
    """`boxes` of one rectangle, shape (4,), with the same values but without numpy's cost per call on
    one-element arrays (about 20 us; the repairs make tens of thousands of single boxes)."""
    s, c = (abs(v) for v in turn(float(rotation)))
    ex, ez = (width * c + depth * s) / 2, (width * s + depth * c) / 2
    return np.array([x - ex, z - ez, x + ex, z + ez], float)


def overlap_many(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(N, M) overlap areas between boxes a (N, 4) and b (M, 4)."""
    ax0, az0, ax1, az1 = (np.ascontiguousarray(c)[:, None] for c in a.T)
    dx = np.minimum(ax1, b[:, 2]) - np.maximum(ax0, b[:, 0])
    dz = np.minimum(az1, b[:, 3]) - np.maximum(az0, b[:, 1])
    np.maximum(dx, 0.0, out=dx)
    np.maximum(dz, 0.0, out=dz)
    return dx * dz



class SweptBoxes:
    """Many boxes (N, 4) sorted once along x, so that overlaps with a few other boxes touch only the
    candidates whose x-range can meet them (a sweep-and-prune broad phase). Used where N is large."""

    def __init__(self, a: np.ndarray):
        self.a = a
        self.order = np.argsort(a[:, 0], kind="stable")
        self.x0, self.z0, self.x1, self.z1 = (np.ascontiguousarray(c) for c in a[self.order].T)
        self.max_width = float((a[:, 2] - a[:, 0]).max()) if len(a) else 0.0

    def overlaps(self, b: np.ndarray):
        """For each box of b (M, 4): (indices into a, overlap areas > 0) of the boxes of a it overlaps. The
        x-ranges are searched for all of b at once."""
        if not len(b):
            return
        none = np.zeros(0, int), np.zeros(0)
        los = np.searchsorted(self.x0, b[:, 0] - self.max_width, side="left").tolist()
        his = np.searchsorted(self.x0, b[:, 2], side="left").tolist()
        for lo, hi, (bx0, bz0, bx1, bz1) in zip(los, his, b.tolist()):
            if hi <= lo:
                yield none
                continue
            dx = np.minimum(self.x1[lo:hi], bx1) - np.maximum(self.x0[lo:hi], bx0)
            dz = np.minimum(self.z1[lo:hi], bz1) - np.maximum(self.z0[lo:hi], bz0)
            hit = (dx > 0) & (dz > 0)
            yield self.order[lo:hi][hit], (dx * dz)[hit]

    def overlapping(self, b: np.ndarray, tol: float, squared: np.ndarray | None = None) -> np.ndarray:
        """Mask of the boxes overlapping some box of b (M, 4) by more than `tol`; with `squared` (N,), the
        squared overlap areas are added to it, box by box of b in order: what a loop over `overlaps` computes,
        to the bit (tested), in one compiled call."""
        add = squared is not None
        return _sweep(self.x0, self.z0, self.x1, self.z1, self.order, self.max_width,
                      np.asarray(b, float).reshape(-1, 4), tol, squared if add else np.zeros(0), add)


@compiled
def _sweep(x0, z0, x1, z1, order, max_width, b, tol, squared, add):
    """`SweptBoxes.overlapping`'s loop, in the same floating-point operations as `overlaps`."""
    mask = np.zeros(len(x0), np.bool_)
    for m in range(b.shape[0]):
        bx0, bz0, bx1, bz1 = b[m, 0], b[m, 1], b[m, 2], b[m, 3]
        for k in range(np.searchsorted(x0, bx0 - max_width, side="left"), np.searchsorted(x0, bx1, side="left")):
            dx = min(x1[k], bx1) - max(x0[k], bx0)
            dz = min(z1[k], bz1) - max(z0[k], bz0)
            if dx > 0 and dz > 0:
                area = dx * dz
                mask[order[k]] |= area > tol
                if add:
                    squared[order[k]] += area * area
    return mask
