"""The relational data prior, learned from 92 of the 120 hand-designed iTHOR rooms (the other 28 fit
the realism judge, see `judge_scene`).

For every room type and ordered pair of floor-standing object types (A, B) it counts, over all
instances of A in rooms that also hold a B: the gap from A to the nearest B (binned), and how A is
turned relative to that B (same way, quarter turn, opposite); for every type, how often it touches a
wall. E_prior of a pose is the normalised surprise -log p of its bin under these counts (Laplace
smoothed), in [0, 1]; pairs never seen together have no prior (0).

    python -m models.energy.prior    # rebuilds models/data/relation_prior.json (deterministic)
"""

from __future__ import annotations

import json
import math
from collections import defaultdict
from functools import cache
from importlib import resources
from pathlib import Path

import numpy as np

from models.constraints.evaluate import gap_of_boxes
from models.world import catalogue
from models.world.catalogue import ithor_scenes

GAP_BINS = (0.0, 0.1, 0.3, 0.6, 1.0, 1.5, 2.5, 4.0)  # left edges, metres; last bin open
TURN_BINS = 3  # |relative yaw| near 0, 90 or 180 degrees
WALL_TOUCH = 0.15
ALPHA = 1.0
POOLED = "*"
COMPANION_GAP, COMPANION_SHARE, COMPANION_SEEN = 1.0, 0.6, 3  # RelationPrior.companion_gap
OUT = Path(__file__).resolve().parent.parent / "data" / "relation_prior.json"


def gap_bin(gap):
    return np.clip(np.searchsorted(GAP_BINS, gap, side="right") - 1, 0, len(GAP_BINS) - 1)


def turn_bin(rel_yaw):
    d = np.abs((np.asarray(rel_yaw, float) + 180.0) % 360.0 - 180.0)
    return np.where(d < 45, 0, np.where(d < 135, 1, 2))


def _box(o) -> tuple[float, float, float, float]:
    return (o["x"] - o["size"][0] / 2, o["z"] - o["size"][2] / 2, o["x"] + o["size"][0] / 2, o["z"] + o["size"][2] / 2)


def standing_objects(scene: dict, types: set[str]) -> list[dict]:
    """The objects of an iTHOR `scene` of one of `types` that stand on the floor itself."""
    return [o for o in scene["objects"] if o["type"] in types and set(o["parents"]) <= {"Floor"}]


def wall_touch(scene: dict, objects: list[dict]) -> list[bool]:
    """For each of `objects`: whether its footprint is within WALL_TOUCH of a wall of `scene`. The walls are the
    extent of everything in the room but the floor slab (which runs under them): windows, light switches and
    paintings sit on the walls."""
    others = [_box(o) for o in scene["objects"] if o["type"] != "Floor"]
    fb = (min(b[0] for b in others), min(b[1] for b in others), max(b[2] for b in others), max(b[3] for b in others))
    return [min(b[0] - fb[0], b[1] - fb[1], fb[2] - b[2], fb[3] - b[3]) <= WALL_TOUCH for b in map(_box, objects)]


def learn(scenes: list[dict], floor_types: set[str]) -> dict:
    """Counts over the floor-standing objects (ProcTHOR's onFloor types) of every iTHOR room."""
    pairs: dict[str, dict[str, list[int]]] = defaultdict(lambda: {"gap": [0] * len(GAP_BINS), "turn": [0] * TURN_BINS})
    walls: dict[str, list[int]] = defaultdict(lambda: [0, 0])
    for scene in scenes:
        standing = standing_objects(scene, floor_types)
        for a, touch in zip(standing, wall_touch(scene, standing)):
            ab = _box(a)
            for room in (scene["room_type"], POOLED):
                walls[f"{room}|{a['type']}"][0] += touch
                walls[f"{room}|{a['type']}"][1] += 1
            by_type: dict[str, list] = defaultdict(list)
            for b in standing:
                if b is not a:
                    by_type[b["type"]].append(b)
            for b_type, bs in by_type.items():
                gaps = gap_of_boxes(np.array(ab), np.array([_box(b) for b in bs]))
                nearest = bs[int(np.argmin(gaps))]
                g = int(gap_bin(float(gaps.min())))
                t = int(turn_bin(a["rotation"] - nearest["rotation"]))
                for room in (scene["room_type"], POOLED):
                    entry = pairs[f"{room}|{a['type']}|{b_type}"]
                    entry["gap"][g] += 1
                    entry["turn"][t] += 1
    return {"gap_bins": list(GAP_BINS), "pairs": dict(sorted(pairs.items())), "walls": dict(sorted(walls.items()))}


def _surprise(counts: list[int]) -> np.ndarray:
    """Per bin: -log p(bin) / max possible, Laplace smoothed: 0 for the most typical bin's neighbourhood, 1 for
    unseen."""
    c = np.asarray(counts, float) + ALPHA
    p = c / c.sum()
    worst = -math.log(ALPHA / c.sum())
    best = -math.log(p.max())
    return np.clip((-np.log(p) - best) / max(worst - best, 1e-9), 0.0, 1.0)


class RelationPrior:
    def __init__(self, data: dict):
        self.pairs = data["pairs"]
        self.walls = data["walls"]
        self._tables: dict[tuple, np.ndarray] = {}  # `_surprise` of a table's entry, made when first asked

    def _surprises(self, table: str, key: str, field: str = "") -> np.ndarray:
        """`_surprise` of a pair's `field` ("gap", "turn") or of a wall entry ([hits, total]), made once."""
        if (table, key, field) not in self._tables:
            entry = getattr(self, table)[key]
            counts = entry[field] if field else [entry[1] - entry[0], entry[0]]
            self._tables[table, key, field] = _surprise(counts)
        return self._tables[table, key, field]

    def _key(self, table: dict, room: str, *types: str) -> str | None:
        for r in (room, POOLED):
            key = "|".join((r, *types))
            if key in table:
                return key
        return None

    def pair_energy(self, room: str, a: str, b: str, gap, rel_yaw) -> np.ndarray:
        """Normalised surprise of A's gap to and turn against B, in [0, 1] (broadcasts over arrays)."""
        key = self._key(self.pairs, room, a, b)
        if key is None:
            return np.zeros(np.broadcast(np.asarray(gap), np.asarray(rel_yaw)).shape)
        return 0.5 * (self._surprises("pairs", key, "gap")[gap_bin(gap)]
                      + self._surprises("pairs", key, "turn")[turn_bin(rel_yaw)])

    def companion_gap(self, room: str, a: str, b: str) -> float | None:
        """If A keeps a B near by habit (of at least `COMPANION_SEEN` A's in rooms with a B, at least
        `COMPANION_SHARE` have their nearest B within `COMPANION_GAP`): the gap bin edge that share stays
        within; else None."""
        key = self._key(self.pairs, room, a, b)
        if key is None:
            return None
        counts = np.asarray(self.pairs[key]["gap"], float)
        edges = (*GAP_BINS[1:], math.inf)  # each bin's upper edge
        share = np.cumsum(counts) / max(counts.sum(), 1.0)
        k = int(np.searchsorted(share, COMPANION_SHARE - 1e-9))
        if counts.sum() < COMPANION_SEEN or edges[k] > COMPANION_GAP:
            return None
        return edges[k]

    def wall_energy(self, room: str, a: str, touching) -> np.ndarray:
        key = self._key(self.walls, room, a)
        touching = np.asarray(touching, bool)
        if key is None:
            return np.zeros(touching.shape)
        return self._surprises("walls", key)[touching.astype(int)]


@cache
def relation_prior() -> RelationPrior:
    return RelationPrior(json.loads(resources.files("models").joinpath("data/relation_prior.json").read_text()))


def judge_scene(scene: str) -> bool:
    """The held-out quarter of the iTHOR rooms (FloorPlan number divisible by 4: 28 of 120, 7 per room
    type) that fits the realism judge (models.metrics.realism); the energy's prior learns from the rest,
    so the reward and the judge are not the same numbers."""
    return int(scene.removeprefix("FloorPlan")) % 4 == 0


def floor_types() -> set[str]:
    cat = catalogue()
    return {n for n, t in cat.types.items() if t.on_floor and not t.pickupable}


def build() -> str:
    scenes = [s for s in ithor_scenes() if not judge_scene(s["scene"])]
    return json.dumps(learn(scenes, floor_types()), sort_keys=True, separators=(",", ":")) + "\n"


if __name__ == "__main__":
    OUT.write_text(build())
    print(f"wrote {OUT}")
