"""Realism: how human-like an arrangement is, judged by habits of the hand-built iTHOR rooms.

A stand-in for the paper's human study and VLM judge (neither can run here). Its statistics are
fitted on the held-out quarter of the iTHOR rooms (`models.energy.prior.judge_scene`: 28 rooms), the
energy's prior on the other 92, so a placer trained on the energy is not judged by its own numbers.

    python -m models.metrics.realism   # rebuilds models/data/realism_stats.json (deterministic)

Fitted, per room type and pooled over all rooms (floor-standing types only, as in the prior):
- wall habit: the share of a type's instances whose footprint is within 0.15 m of a wall; a type with
  at least 3 instances and a share >= 0.7 "stands against a wall", <= 0.3 "stands free";
- companions: a type pair (A, B) such that, in at least 60 % of the rooms holding both (at least 2),
  A's nearest B is within 1.0 m (chairs at their table, a side table by the bed); the pair's allowed
  gap is the largest such gap seen, at least 0.3 m.

The score of a layout: one check per placed object with a wall habit (a wall-standing object must
touch a wall and face into the room, i.e. its front points away from a wall it touches: in a corner,
from either of the two; a free-standing one must not touch a wall), and one per placed object A of a companion pair whose B is in the plan (its
nearest B within the allowed gap). Realism = checks passed / checks, or None (n/a) without checks.
An unplaced object fails all its checks, so leaving objects out never scores better.
"""

from __future__ import annotations

import json
from collections import defaultdict
from dataclasses import dataclass
from functools import cache
from importlib import resources
from pathlib import Path

import numpy as np

from models.constraints.evaluate import gap_of_boxes
from models.energy.prior import POOLED, WALL_TOUCH, _box, floor_types, judge_scene, standing_objects, wall_touch
from models.geometry import boxes, front
from models.values import ConstraintPlan, Layout
from models.world.catalogue import ithor_scenes

HABIT = 0.7
MIN_INSTANCES = 3
COMPANION_GAP = 1.0
COMPANION_SHARE = 0.6
MIN_ROOMS = 2
MIN_ALLOWED_GAP = 0.3
OUT = Path(__file__).resolve().parent.parent / "data" / "realism_stats.json"


def fit(scenes: list[dict], types: set[str]) -> dict:
    wall: dict[str, list[int]] = defaultdict(lambda: [0, 0])
    pair_rooms: dict[str, list] = defaultdict(lambda: [0, 0, 0.0])  # rooms with both, rooms close, largest gap
    for scene in scenes:
        standing = standing_objects(scene, types)
        for a, touch in zip(standing, wall_touch(scene, standing)):
            for room in (scene["room_type"], POOLED):
                wall[f"{room}|{a['type']}"][0] += touch
                wall[f"{room}|{a['type']}"][1] += 1
        present = {o["type"] for o in standing}
        for a_type in present:
            for b_type in present:
                if a_type == b_type:
                    continue
                theirs = np.array([_box(b) for b in standing if b["type"] == b_type])
                gaps = [float(gap_of_boxes(np.array(_box(a)), theirs).min()) for a in standing if a["type"] == a_type]
                close = [g for g in gaps if g <= COMPANION_GAP]
                for room in (scene["room_type"], POOLED):
                    entry = pair_rooms[f"{room}|{a_type}|{b_type}"]
                    entry[0] += 1
                    entry[1] += len(close) == len(gaps)
                    entry[2] = max(entry[2], max(close, default=0.0))
    habits = {k: round(h / n, 4) for k, (h, n) in wall.items() if n >= MIN_INSTANCES and (h / n >= HABIT or h / n <= 1 - HABIT)}
    companions = {k: round(max(g, MIN_ALLOWED_GAP), 4) for k, (both, close, g) in pair_rooms.items()
                  if both >= MIN_ROOMS and close / both >= COMPANION_SHARE}
    return {"scenes": sorted(s["scene"] for s in scenes), "wall": dict(sorted(habits.items())),
            "companions": dict(sorted(companions.items()))}


def build() -> str:
    scenes = [s for s in ithor_scenes() if judge_scene(s["scene"])]
    return json.dumps(fit(scenes, floor_types()), sort_keys=True, indent=0) + "\n"


@cache
def stats() -> dict:
    return json.loads(resources.files("models").joinpath("data/realism_stats.json").read_text())


def _lookup(table: dict, room: str, *types: str):
    for r in (room, POOLED):
        key = "|".join((r, *types))
        if key in table:
            return table[key]
    return None


@dataclass(frozen=True)
class Check:
    """One check of the judge: `object_id`'s wall habit ("wall" or "free") or its companion `other` type."""

    object_id: str
    kind: str  # "wall", "free" or "companion"
    passed: bool
    other: str = ""  # the companion type


def checks(plan: ConstraintPlan, layout: Layout) -> list[Check]:
    """Every check of one layout, in the plan's object order."""
    st = stats()
    room = plan.room
    placed = {p.id: p for p in layout.placements}
    box = {k: tuple(float(v) for v in np.reshape(boxes(p.x, p.z, p.size.x, p.size.z, p.rotation), 4))
           for k, p in placed.items()}
    out = []
    for o in plan.objects:
        share = _lookup(st["wall"], room.type, o.type)
        p = placed.get(o.id)
        if share is not None:
            passed = False
            if p is not None:
                b = box[o.id]
                dists = {"west": b[0], "south": b[1], "east": room.width - b[2], "north": room.depth - b[3]}
                touched = [wall for wall, d in dists.items() if d <= WALL_TOUCH]
                if share >= HABIT:
                    fx, fz = front(p.rotation)
                    inward = {"west": fx, "south": fz, "east": -fx, "north": -fz}
                    passed = any(inward[wall] > 0.5 for wall in touched)
                else:
                    passed = not touched
            out.append(Check(o.id, "wall" if share >= HABIT else "free", passed))
        for target_type in sorted({t.type for t in plan.objects if t.type != o.type}):
            allowed = _lookup(st["companions"], room.type, o.type, target_type)
            if allowed is None:
                continue
            targets = [box[t.id] for t in plan.objects if t.type == target_type and t.id in placed]
            passed = p is not None and bool(targets) and \
                float(gap_of_boxes(np.array(box[o.id]), np.array(targets)).min()) <= allowed + 1e-9
            out.append(Check(o.id, "companion", passed, target_type))
    return out


def realism_checks(plan: ConstraintPlan, layout: Layout) -> tuple[int, int]:
    """(checks passed, checks) of one layout."""
    found = checks(plan, layout)
    return sum(c.passed for c in found), len(found)


def passed_share(found: list[Check]) -> float | None:
    """Realism of a layout's `checks`: the share passed, None without checks."""
    return sum(c.passed for c in found) / len(found) if found else None


def realism(plan: ConstraintPlan, layout: Layout) -> float | None:
    return passed_share(checks(plan, layout))


if __name__ == "__main__":
    OUT.write_text(build())
    print(f"wrote {OUT}")
