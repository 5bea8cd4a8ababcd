"""Two harder constraint sets where differences between solvers show (issue 7).

- `dense`  the `seen` validation plans (instructions never seen in training) in rooms shrunk until
           furniture covers 50-65 % of the floor, with several relations per object written the way
           real LLM output is: drawn at random from the whole vocabulary and from all objects of the
           plan, so some subsets conflict (`near` and `far` of one target, `left of` and `right of`)
           or cannot all be met. Nothing here is derived from any solver's predicates or candidates.
- `human`  plans read off the 120 hand-built iTHOR rooms: their floor-standing objects with real
           sizes, the room's extent, and constraints that describe the arrangement people made
           (measured with this module's own plain geometry: touching a wall, nearest neighbour,
           facing). Each record keeps the human layout as `reference`, so a solver's layout can be
           compared with it. iTHOR has no door positions: the door is put where the walls leave the
           widest free stretch (a stand-in, named here and in the README). The task object is the
           room's main piece (fridge, bed, sofa, toilet) as the anchor.
"""

from __future__ import annotations

import math
import random

import numpy as np

from models.constraints.evaluate import gap_of_boxes
from models.energy.prior import _box, floor_types, ithor_scenes
from models.values import ConstraintPlan, Layout, Placement, Size, Timing

DENSE_PLANS = 300
DENSE_COVER = (0.50, 0.65)
DENSE_RELATIONS = (2, 4)
VOCABULARY = ("near", "far", "in front of", "side of", "left of", "right of", "face to", "around",
              "center aligned", "behind")
HUMAN_TOUCH = 0.15  # m: "against the wall"
HUMAN_NEAR = 0.6  # m: "near" its nearest neighbour
HUMAN_FACE_DEG = 30.0
DOOR_WIDTH, DOOR_DEPTH = 1.0, 0.9
ANCHORS = {"kitchen": ("Fridge", "CounterTop"), "bedroom": ("Bed",), "living room": ("Sofa", "ArmChair"),
           "bathroom": ("Toilet", "Sink")}


# ---- dense ------------------------------------------------------------------------------------------

def densify(plan: ConstraintPlan, rng: random.Random) -> ConstraintPlan | None:
    """The plan in a room shrunk to a coverage drawn from DENSE_COVER, with LLM-like random relations."""
    area = sum(o.size.x * o.size.z for o in plan.objects)
    room = plan.room
    scale = math.sqrt(area / rng.uniform(*DENSE_COVER) / (room.width * room.depth))
    if scale >= 1.0:
        scale = 1.0
    width, depth = round(room.width * scale, 2), round(room.depth * scale, 2)
    longest = max(max(o.size.x, o.size.z) for o in plan.objects)
    if min(width, depth) < longest + 0.1:
        return None

    def shrink(op, length_before, length_after):
        centre = min(max(op.center * length_after / length_before, op.width / 2 + 0.001), length_after - op.width / 2 - 0.001)
        return op.model_copy(update={"center": round(centre, 3)})

    def scaled(ops):
        return [shrink(op, room.wall_length(op.wall), width if op.wall in ("south", "north") else depth)
                for op in ops if op.width + 0.01 <= (width if op.wall in ("south", "north") else depth)]

    new_room = room.model_copy(update={"width": width, "depth": depth, "doors": scaled(room.doors),
                                       "windows": scaled(room.windows)})
    ids = [o.id for o in plan.objects]
    lines = []
    for oid in ids:
        parts = [oid, rng.choice(("edge", "edge", "middle"))]
        others = [t for t in ids if t != oid]
        for _ in range(rng.randint(*DENSE_RELATIONS) if others else 0):
            parts.append(f"{rng.choice(VOCABULARY)}, {rng.choice(others)}")
        lines.append(" | ".join(parts))
    return plan.model_copy(update={"id": plan.id.replace("seen", "dense"), "room": new_room,
                                   "constraints": "\n".join(lines)})


def build_dense(seen_validation: list) -> list:
    from models.datasets.constraint_sets import SEED, PlanRecord
    rng = random.Random(f"{SEED}-dense")
    out = []
    for record in seen_validation:
        plan = densify(record.plan, rng)
        if plan is not None:
            out.append(PlanRecord("test", record.instruction, plan))
        if len(out) == DENSE_PLANS:
            break
    return out


# ---- human ------------------------------------------------------------------------------------------

def _door(width: float, depth: float, boxes: list) -> dict:
    """The door where a 1 m wide, 0.9 m deep entrance zone overlaps the least furniture (then the most central)."""
    best = None
    for wall in ("south", "north", "west", "east"):
        length = width if wall in ("south", "north") else depth
        steps = int((length - DOOR_WIDTH) / 0.1) + 1
        for k in range(max(steps, 0)):
            c = DOOR_WIDTH / 2 + 0.1 * k
            lo, hi = c - DOOR_WIDTH / 2, c + DOOR_WIDTH / 2
            zone = {"south": (lo, 0, hi, DOOR_DEPTH), "north": (lo, depth - DOOR_DEPTH, hi, depth),
                    "west": (0, lo, DOOR_DEPTH, hi), "east": (width - DOOR_DEPTH, lo, width, hi)}[wall]
            blocked = sum(max(0, min(zone[2], b[2]) - max(zone[0], b[0])) * max(0, min(zone[3], b[3]) - max(zone[1], b[1]))
                          for b in boxes)
            key = (round(blocked, 4), abs(c - length / 2))
            if best is None or key < best[0]:
                best = (key, {"wall": wall, "center": round(c, 3), "width": DOOR_WIDTH})
    return best[1]


def human_plan(scene: dict, types: set[str]) -> tuple[ConstraintPlan, Layout] | None:
    others = [_box(o) for o in scene["objects"] if o["type"] != "Floor"]
    x0, z0 = min(b[0] for b in others), min(b[1] for b in others)
    width, depth = max(b[2] for b in others) - x0, max(b[3] for b in others) - z0
    standing = [o for o in scene["objects"] if o["type"] in types and set(o["parents"]) <= {"Floor"}]
    if len(standing) < 2:
        return None
    counts: dict[str, int] = {}
    objects, placements, boxes = [], [], []
    for o in standing:
        k = counts[o["type"]] = counts.get(o["type"], -1) + 1
        oid = f"{o['type'].lower()}-{k}"
        rot = round(o["rotation"] / 90.0) % 4 * 90.0
        w, d = (o["size"][0], o["size"][2]) if rot in (0.0, 180.0) else (o["size"][2], o["size"][0])
        x, z = o["x"] - x0, o["z"] - z0
        objects.append({"id": oid, "type": o["type"], "size": {"x": round(w, 3), "y": max(round(o["size"][1], 3), 0.01),
                                                               "z": round(d, 3)}, "role": "context"})
        placements.append((oid, x, z, rot, w, d))
        b = _box(o)
        boxes.append((b[0] - x0, b[1] - z0, b[2] - x0, b[3] - z0))
    for anchor_type in ANCHORS.get(scene["room_type"], ()):
        hit = next((ob for ob in objects if ob["type"] == anchor_type), None)
        if hit is not None:
            hit["role"] = "anchor"
            break
    lines = []
    for i, (oid, x, z, rot, w, d) in enumerate(placements):
        b = boxes[i]
        wall = min(b[0], b[1], width - b[2], depth - b[3])
        parts = [oid, "edge" if wall <= HUMAN_TOUCH else "middle"]
        others = [j for j in range(len(placements)) if j != i]
        gaps = gap_of_boxes(np.array(b), np.array([boxes[j] for j in others]))
        g, j = float(gaps.min()), others[int(np.argmin(gaps))]
        if g <= HUMAN_NEAR:
            parts.append(f"near, {placements[j][0]}")
        fx, fz = math.sin(math.radians(rot)), math.cos(math.radians(rot))
        tx, tz = placements[j][1] - x, placements[j][2] - z
        norm = math.hypot(tx, tz)
        if g <= 1.5 and norm > 0 and math.degrees(math.acos(max(-1, min(1, (fx * tx + fz * tz) / norm)))) <= HUMAN_FACE_DEG:
            parts.append(f"face to, {placements[j][0]}")
        lines.append(" | ".join(parts))
    room = {"type": scene["room_type"], "width": round(width, 3), "depth": round(depth, 3),
            "doors": [_door(width, depth, boxes)]}
    plan = ConstraintPlan.model_validate({"id": f"human-{scene['scene']}", "room": room, "objects": objects,
                                          "constraints": "\n".join(lines)})
    sizes = {ob["id"]: ob["size"] for ob in objects}
    layout = Layout(plan_id=plan.id, solver="human", seed=0, timing=Timing(total_s=0.0, per_object_s=0.0),
                    placements=[Placement(id=oid, type=next(ob["type"] for ob in objects if ob["id"] == oid),
                                          x=round(x, 4), z=round(z, 4), rotation=rot, size=Size(**sizes[oid]))
                                for oid, x, z, rot, w, d in placements])
    return plan, layout


def build_human() -> list:
    from models.datasets.constraint_sets import PlanRecord
    types = floor_types()
    out = []
    for scene in sorted(ithor_scenes(), key=lambda s: int(s["scene"].removeprefix("FloorPlan"))):
        made = human_plan(scene, types)
        if made is not None:
            out.append(PlanRecord("test", f"iTHOR {scene['scene']} as people arranged it", made[0], made[1]))
    return out
