"""The scorer interface and the arrangement statistics every scorer can use."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from models.energy.prior import WALL_TOUCH, relation_prior

FEATURES = ("wall_prior", "pair_prior", "wall_share", "faces_in", "overlap", "nearest_gap", "occupancy",
            "off_centre")


@dataclass(frozen=True)
class LayoutItem:
    type: str
    x: float
    z: float
    rotation: float
    width: float
    depth: float


@dataclass(frozen=True)
class SemanticScore:
    features: np.ndarray  # h_vl, float32 (len(FEATURES),)
    score: float  # r_vlm in [0, 1]: how human-like the arrangement looks


class SemanticScorer(Protocol):
    dim: int

    def score(self, room_type: str, width: float, depth: float, items: list[LayoutItem]) -> SemanticScore: ...


def items_of(placed, types: dict[str, str]) -> list[LayoutItem]:
    """Placement-like objects (id, x, z, rotation, width|size, depth) -> items."""
    out = []
    for p in placed:
        w, d = (p.size.x, p.size.z) if hasattr(p, "size") else (p.width, p.depth)
        out.append(LayoutItem(types[p.id], p.x, p.z, p.rotation, w, d))
    return out


def _boxes(items: list[LayoutItem]) -> np.ndarray:
    out = []
    for it in items:
        turned = round(it.rotation / 90) % 2 == 1
        w, d = (it.depth, it.width) if turned else (it.width, it.depth)
        out.append([it.x - w / 2, it.z - d / 2, it.x + w / 2, it.z + d / 2])
    return np.array(out, float).reshape(-1, 4)


def arrangement_features(room_type: str, width: float, depth: float, items: list[LayoutItem]) -> np.ndarray:
    """Eight statistics of how objects stand in the room (0 for an empty layout)."""
    f = np.zeros(len(FEATURES), np.float32)
    if not items:
        return f
    prior = relation_prior()
    b = _boxes(items)
    wall_gap = np.stack([b[:, 0], b[:, 1], width - b[:, 2], depth - b[:, 3]], 1)  # west, south, east, north
    touching = wall_gap.min(1) <= WALL_TOUCH
    f[0] = np.mean([float(prior.wall_energy(room_type, it.type, np.array([t]))[0]) for it, t in zip(items, touching)])
    n = len(items)
    gx = np.maximum(0, np.maximum(b[:, None, 0] - b[None, :, 2], b[None, :, 0] - b[:, None, 2]))
    gz = np.maximum(0, np.maximum(b[:, None, 1] - b[None, :, 3], b[None, :, 1] - b[:, None, 3]))
    gap = np.hypot(gx, gz) + np.eye(n) * 1e9
    if n > 1:
        nearest = gap.argmin(1)
        f[1] = np.mean([float(prior.pair_energy(room_type, items[i].type, items[j].type, np.array([gap[i, j]]),
                                                np.array([items[i].rotation - items[j].rotation]))[0])
                        for i, j in enumerate(nearest)])
        f[5] = float(np.minimum(gap.min(1), 2.0).mean() / 2)
    f[2] = touching.mean()
    r = np.radians([it.rotation for it in items])
    front = np.stack([np.sin(r), np.cos(r)], 1)
    wall_normal_in = np.array([[1, 0], [0, 1], [-1, 0], [0, -1]], float)[wall_gap.argmin(1)]
    faces_in = (front * wall_normal_in).sum(1) > 0.5
    f[3] = faces_in[touching].mean() if touching.any() else 0.0
    ix = np.maximum(0, np.minimum(b[:, None, 2], b[None, :, 2]) - np.maximum(b[:, None, 0], b[None, :, 0]))
    iz = np.maximum(0, np.minimum(b[:, None, 3], b[None, :, 3]) - np.maximum(b[:, None, 1], b[None, :, 1]))
    area = (b[:, 2] - b[:, 0]) * (b[:, 3] - b[:, 1])
    f[4] = float(np.triu(ix * iz, 1).sum() / max(area.sum(), 1e-6))
    f[6] = float(area.sum() / (width * depth))
    cx, cz = (b[:, 0] + b[:, 2]) / 2, (b[:, 1] + b[:, 3]) / 2
    f[7] = float(np.hypot((np.average(cx, weights=area) - width / 2) / width,
                          (np.average(cz, weights=area) - depth / 2) / depth))
    return f
