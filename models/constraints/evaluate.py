"""Scores constraints on placed objects: for each, an energy (0 whenever the constraint is met, growing
with the violation) and a satisfied flag, exactly as the table of constraints.md defines them.

Everything is vectorised: A and B are arrays of poses that broadcast against each other (N candidates
of A against one placed B, or one placed A against N candidates of B), so a placer scores all its
candidates at once. Footprints are treated as axis-aligned boxes, which is exact for rotations that
are multiples of 90 degrees.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from models.geometry import boxes, one_box

EDGE_TOL = 0.05
MIDDLE_MIN = 0.4
NEAR_MAX = 1.0
FAR_MIN = 1.5
FRONT_MAX_GAP, LATERAL_SLACK = 1.5, 0.3
SIDE_MAX_GAP = 0.8
AROUND_MAX_GAP = 0.6
FACE_MAX_DEG = 45.0
ALIGN_TOL = 0.1
FLOAT_TOL = 1e-9  # a length or angle this close to a threshold meets it: the judge's polygon gaps and the placers'
# box gaps, or an angle from arccos, differ from the exact value in the last bits


@dataclass(frozen=True)
class Poses:
    """N candidate poses of one object (or one pose, N = 1)."""

    x: np.ndarray
    z: np.ndarray
    rotation: np.ndarray
    width: float
    depth: float

    @classmethod
    def one(cls, x: float, z: float, rotation: float, width: float, depth: float) -> Poses:
        return cls(np.array([x], float), np.array([z], float), np.array([rotation], float), width, depth)

    def boxes(self) -> np.ndarray:
        return self._boxes

    @cached_property
    def _boxes(self) -> np.ndarray:
        if len(self.x) == 1:
            return one_box(self.x[0], self.z[0], self.width, self.depth, self.rotation[0])[None]
        return boxes(self.x, self.z, self.width, self.depth, self.rotation)

    def fronts(self) -> tuple[np.ndarray, np.ndarray]:
        return self._fronts

    @cached_property
    def _fronts(self) -> tuple[np.ndarray, np.ndarray]:
        r = np.radians(self.rotation)
        return np.sin(r), np.cos(r)


def box_gap(a: Poses, b: Poses) -> np.ndarray:
    """Elementwise shortest distance between the boxes of A and B (broadcast)."""
    return gap_of_boxes(a.boxes(), b.boxes())


def gap_of_boxes(ba: np.ndarray, bb: np.ndarray) -> np.ndarray:
    """Elementwise shortest distance between boxes [xmin, zmin, xmax, zmax] (..., 4) (broadcast)."""
    dx = np.maximum(0, np.maximum(ba[..., 0] - bb[..., 2], bb[..., 0] - ba[..., 2]))
    dz = np.maximum(0, np.maximum(ba[..., 1] - bb[..., 3], bb[..., 1] - ba[..., 3]))
    return np.hypot(dx, dz)


def _angle_between(ux, uz, vx, vz) -> np.ndarray:
    """Angle in degrees between direction fields u and v."""
    norm = np.hypot(ux, uz) * np.hypot(vx, vz)
    cos = np.where(norm > 0, (ux * vx + uz * vz) / np.maximum(norm, 1e-12), 1.0)
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))


def _frame(a: Poses, b: Poses) -> tuple[np.ndarray, np.ndarray]:
    """A's centre in B's frame: (ahead along front(B), lateral along right(B))."""
    br = np.radians(b.rotation)
    dx, dz = a.x - b.x, a.z - b.z
    ahead = dx * np.sin(br) + dz * np.cos(br)
    lateral = dx * np.cos(br) - dz * np.sin(br)
    return ahead, lateral


def _relu(v):
    return np.maximum(v, 0.0)


def relation(name: str, a: Poses, b: Poses, gap: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(energy, satisfied) of `A name B` for every pose; `gap` overrides the box gap (exact polygons)."""
    return _relation(name, a, b, gap, True)


def relation_met(name: str, a: Poses, b: Poses) -> np.ndarray:
    """Whether `A name B` holds for every pose: `relation`'s second half, without computing its energy (the
    polish counts the constraints met by thousands of poses at a time)."""
    return _relation(name, a, b, None, False)[1]


def _relation(name: str, a: Poses, b: Poses, gap: np.ndarray | None, energy: bool
              ) -> tuple[np.ndarray | None, np.ndarray]:
    """(energy if `energy` else None, satisfied) of `A name B`: one definition of each relation for both."""
    def _gap(a, b):
        return gap if gap is not None else box_gap(a, b)

    if name == "near":
        g = _gap(a, b)
        return _relu(g - NEAR_MAX) if energy else None, g <= NEAR_MAX + FLOAT_TOL
    if name == "far":
        g = _gap(a, b)
        return _relu(FAR_MIN - g) if energy else None, g >= FAR_MIN - FLOAT_TOL
    if name in ("in front of", "behind"):
        ahead, lateral = _frame(a, b)
        if name == "behind":
            ahead = -ahead
        g = _gap(a, b)
        lat_max = b.width / 2 + LATERAL_SLACK
        ok = (ahead > b.depth / 2) & (np.abs(lateral) <= lat_max + FLOAT_TOL) & (g <= FRONT_MAX_GAP + FLOAT_TOL)
        if not energy:
            return None, ok
        return _relu(b.depth / 2 - ahead) + _relu(np.abs(lateral) - lat_max) + _relu(g - FRONT_MAX_GAP), ok
    if name in ("side of", "left of", "right of"):
        ahead, lateral = _frame(a, b)
        side = {"side of": np.abs(lateral), "left of": -lateral, "right of": lateral}[name]
        g = _gap(a, b)
        ahead_max = b.depth / 2 + LATERAL_SLACK
        ok = (side > b.width / 2) & (np.abs(ahead) <= ahead_max + FLOAT_TOL) & (g <= SIDE_MAX_GAP + FLOAT_TOL)
        if not energy:
            return None, ok
        return _relu(b.width / 2 - side) + _relu(np.abs(ahead) - ahead_max) + _relu(g - SIDE_MAX_GAP), ok
    if name == "face to":
        fx, fz = a.fronts()
        angle = _angle_between(fx, fz, b.x - a.x, b.z - a.z)
        return _relu(angle - FACE_MAX_DEG) / 90.0 if energy else None, angle <= FACE_MAX_DEG + FLOAT_TOL
    if name == "face same as":
        diff = np.abs((a.rotation - b.rotation + 180.0) % 360.0 - 180.0)
        return _relu(diff - FACE_MAX_DEG) / 90.0 if energy else None, diff <= FACE_MAX_DEG + FLOAT_TOL
    if name == "around":
        g = _gap(a, b)
        face_e, face_ok = _relation("face to", a, b, None, energy)
        ok = (g <= AROUND_MAX_GAP + FLOAT_TOL) & face_ok
        return _relu(g - AROUND_MAX_GAP) + face_e if energy else None, ok
    if name == "center aligned":
        off = np.minimum(np.abs(a.x - b.x), np.abs(a.z - b.z))
        return _relu(off - ALIGN_TOL) if energy else None, off <= ALIGN_TOL + FLOAT_TOL
    raise ValueError(f"unknown constraint {name!r}")


def back_wall_distance(a: Poses, room_width: float, room_depth: float) -> np.ndarray:
    """Distance from the middle of A's back side to the wall behind it, measured along -front(A)."""
    fx, fz = a.fronts()
    bx, bz = a.x - fx * a.depth / 2, a.z - fz * a.depth / 2
    with np.errstate(divide="ignore", invalid="ignore"):
        tx = np.where(fx > 1e-9, bx / fx, np.where(fx < -1e-9, (room_width - bx) / -fx, np.inf))
        tz = np.where(fz > 1e-9, bz / fz, np.where(fz < -1e-9, (room_depth - bz) / -fz, np.inf))
    return np.minimum(tx, tz)


def wall_clearance(a: Poses, room_width: float, room_depth: float) -> np.ndarray:
    b = a.boxes()
    return np.min(np.stack([b[:, 0], b[:, 1], room_width - b[:, 2], room_depth - b[:, 3]]), axis=0)


def placement(name: str, a: Poses, room_width: float, room_depth: float,
              clearance: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(energy, satisfied) of the global placement `edge` or `middle`; `clearance` overrides the box one."""
    c = clearance if clearance is not None else wall_clearance(a, room_width, room_depth)
    if name == "edge":
        d = back_wall_distance(a, room_width, room_depth)
        return _relu(np.abs(d) - EDGE_TOL), (np.abs(d) <= EDGE_TOL + FLOAT_TOL) & (c >= -1e-6)
    if name == "middle":
        return _relu(MIDDLE_MIN - c), c >= MIDDLE_MIN - FLOAT_TOL
    raise ValueError(f"unknown placement {name!r}")
