"""The shape builders: object type -> family -> parts -> one triangle mesh."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

CYLINDER_SIDES = 8


@dataclass(frozen=True)
class Part:
    """A box or an upright cylinder: centre and extents (x, y, z) in the object's frame; `shade` darkens
    secondary parts (legs, trims) in exports that colour faces."""

    kind: str  # "box" | "cylinder"
    centre: tuple[float, float, float]
    extents: tuple[float, float, float]
    shade: float = 1.0


def _box(x0, y0, z0, x1, y1, z1, shade=1.0) -> Part:
    """A box from its min and max corners."""
    return Part("box", ((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2), (x1 - x0, y1 - y0, z1 - z0), shade)


def _legs(w, h, d, top_y, leg, inset=0.0, shade=0.7) -> list[Part]:
    """Four square legs from the floor (-h/2) up to `top_y`, at the corners."""
    out = []
    for sx in (-1, 1):
        for sz in (-1, 1):
            cx, cz = sx * (w / 2 - inset - leg / 2), sz * (d / 2 - inset - leg / 2)
            out.append(_box(cx - leg / 2, -h / 2, cz - leg / 2, cx + leg / 2, top_y, cz + leg / 2, shade))
    return out


def table(w, h, d) -> list[Part]:
    top = min(0.05, 0.15 * h)
    leg = min(0.06, 0.15 * min(w, d))
    return [_box(-w / 2, h / 2 - top, -d / 2, w / 2, h / 2, d / 2)] + _legs(w, h, d, h / 2 - top, leg, 0.02 * w)


def chair(w, h, d) -> list[Part]:
    seat_y = -h / 2 + 0.45 * h
    seat = 0.06 * h
    back = min(0.08, 0.15 * d)
    leg = min(0.05, 0.15 * min(w, d))
    return ([_box(-w / 2, seat_y - seat, -d / 2, w / 2, seat_y, d / 2),
             _box(-w / 2, seat_y, -d / 2, w / 2, h / 2, -d / 2 + back)]
            + _legs(w, h, d, seat_y - seat, leg))


def stool(w, h, d) -> list[Part]:
    seat = min(0.06, 0.15 * h)
    leg = min(0.05, 0.2 * min(w, d))
    return [_box(-w / 2, h / 2 - seat, -d / 2, w / 2, h / 2, d / 2)] + _legs(w, h, d, h / 2 - seat, leg, 0.05 * w)


def sofa(w, h, d) -> list[Part]:
    arm = min(0.2, 0.15 * w)
    seat_top = -h / 2 + 0.5 * h
    back = min(0.25, 0.3 * d)
    arm_top = -h / 2 + 0.7 * h
    return [_box(-w / 2 + arm, -h / 2, -d / 2 + back, w / 2 - arm, seat_top, d / 2),
            _box(-w / 2, -h / 2, -d / 2, w / 2, h / 2, -d / 2 + back, 0.85),
            _box(-w / 2, -h / 2, -d / 2 + back, -w / 2 + arm, arm_top, d / 2, 0.85),
            _box(w / 2 - arm, -h / 2, -d / 2 + back, w / 2, arm_top, d / 2, 0.85)]


def bed(w, h, d) -> list[Part]:
    head = min(0.1, 0.08 * d)
    frame_top = -h / 2 + 0.25 * h
    mattress_top = -h / 2 + 0.45 * h
    return [_box(-w / 2, -h / 2, -d / 2 + head, w / 2, frame_top, d / 2, 0.7),
            _box(-w / 2 + 0.03, frame_top, -d / 2 + head, w / 2 - 0.03, mattress_top, d / 2 - 0.03),
            _box(-w / 2 + 0.1 * w, mattress_top, -d / 2 + head, w / 2 - 0.1 * w, mattress_top + 0.08 * h,
                 -d / 2 + head + 0.2 * d),
            _box(-w / 2, -h / 2, -d / 2, w / 2, h / 2, -d / 2 + head, 0.7)]


def fridge(w, h, d) -> list[Part]:
    gap = 0.02
    split = h / 2 - 0.35 * h
    handle = min(0.03, 0.1 * d)
    body_front = d / 2 - handle
    return [_box(-w / 2, -h / 2, -d / 2, w / 2, split - gap / 2, body_front),
            _box(-w / 2, split + gap / 2, -d / 2, w / 2, h / 2, body_front),
            _box(w / 2 - 0.12 * w, split + 0.1 * h, body_front, w / 2 - 0.08 * w, h / 2 - 0.05 * h, d / 2, 0.5),
            _box(w / 2 - 0.12 * w, split - 0.3 * h, body_front, w / 2 - 0.08 * w, split - 0.05 * h, d / 2, 0.5)]


def counter(w, h, d) -> list[Part]:
    top = min(0.05, 0.1 * h)
    plinth = min(0.1, 0.12 * h)
    inset = min(0.05, 0.1 * d)
    return [_box(-w / 2, h / 2 - top, -d / 2, w / 2, h / 2, d / 2, 0.8),
            _box(-w / 2 + 0.01, -h / 2 + plinth, -d / 2, w / 2 - 0.01, h / 2 - top, d / 2 - inset),
            _box(-w / 2 + 0.01, -h / 2, -d / 2, w / 2 - 0.01, -h / 2 + plinth, d / 2 - 2 * inset, 0.6)]


def shelf(w, h, d) -> list[Part]:
    board = min(0.03, 0.1 * d)
    parts = [_box(-w / 2, -h / 2, -d / 2, -w / 2 + board, h / 2, d / 2, 0.8),
             _box(w / 2 - board, -h / 2, -d / 2, w / 2, h / 2, d / 2, 0.8),
             _box(-w / 2, -h / 2, -d / 2, w / 2, h / 2, -d / 2 + board, 0.6)]
    levels = max(2, min(6, int(h / 0.35) + 1))
    for k in range(levels):
        y = -h / 2 + k * (h - board) / (levels - 1)
        parts.append(_box(-w / 2 + board, y, -d / 2 + board, w / 2 - board, y + board, d / 2))
    return parts


def lamp(w, h, d) -> list[Part]:
    pole = 0.03 + 0.05 * min(w, d)
    return [Part("cylinder", (0, -h / 2 + 0.015, 0), (0.6 * w, 0.03, 0.6 * d), 0.6),
            Part("cylinder", (0, 0, 0), (pole, h, pole), 0.6),
            Part("cylinder", (0, h / 2 - 0.125 * h, 0), (w, 0.25 * h, d))]


def television(w, h, d) -> list[Part]:
    stand = 0.12 * h
    return [_box(-w / 2, -h / 2 + stand, -d / 4, w / 2, h / 2, d / 4),
            _box(-0.15 * w, -h / 2, -d / 2, 0.15 * w, -h / 2 + stand, d / 2, 0.6)]


def toilet(w, h, d) -> list[Part]:
    tank = 0.3 * d
    return [_box(-w / 2, -h / 2, -d / 2, w / 2, h / 2, -d / 2 + tank, 0.9),
            _box(-0.3 * w, -h / 2, -d / 2 + tank, 0.3 * w, -h / 2 + 0.45 * h, d / 2 - 0.2 * d, 0.8),
            _box(-w / 2, -h / 2 + 0.45 * h, -d / 2 + tank, w / 2, -h / 2 + 0.55 * h, d / 2)]


def tub(w, h, d) -> list[Part]:
    rim = min(0.08, 0.15 * min(w, d))
    return [_box(-w / 2, -h / 2, -d / 2, w / 2, -h / 2 + 0.2 * h, d / 2, 0.8),
            _box(-w / 2, -h / 2, -d / 2, -w / 2 + rim, h / 2, d / 2),
            _box(w / 2 - rim, -h / 2, -d / 2, w / 2, h / 2, d / 2),
            _box(-w / 2 + rim, -h / 2, -d / 2, w / 2 - rim, h / 2, -d / 2 + rim),
            _box(-w / 2 + rim, -h / 2, d / 2 - rim, w / 2 - rim, h / 2, d / 2)]


def bin_(w, h, d) -> list[Part]:
    return [Part("cylinder", (0, -0.05 * h, 0), (0.92 * w, 0.9 * h, 0.92 * d)),
            Part("cylinder", (0, h / 2 - 0.05 * h, 0), (w, 0.1 * h, d), 0.7)]


def appliance(w, h, d) -> list[Part]:
    """Washing machine, dryer: a body and a round door on the front."""
    door = 0.3 * min(w, h)
    return [_box(-w / 2, -h / 2, -d / 2, w / 2, h / 2, d / 2 - 0.02),
            _box(-door, -door, d / 2 - 0.02, door, door, d / 2, 0.5)]


def block(w, h, d) -> list[Part]:
    return [_box(-w / 2, -h / 2, -d / 2, w / 2, h / 2, d / 2)]


FAMILIES: dict[str, tuple[Callable[[float, float, float], list[Part]], tuple[str, ...]]] = {
    "table": (table, ("DiningTable", "CoffeeTable", "SideTable", "Desk", "TVStand")),
    "chair": (chair, ("Chair",)),
    "stool": (stool, ("Stool", "Ottoman")),
    "sofa": (sofa, ("Sofa", "ArmChair")),
    "bed": (bed, ("Bed", "DogBed")),
    "fridge": (fridge, ("Fridge",)),
    "counter": (counter, ("CounterTop", "Cabinet", "Dresser", "Drawer", "Sink", "Safe")),
    "shelf": (shelf, ("Shelf", "ShelvingUnit")),
    "lamp": (lamp, ("FloorLamp", "DeskLamp")),
    "television": (television, ("Television",)),
    "toilet": (toilet, ("Toilet",)),
    "tub": (tub, ("Bathtub", "BathtubBasin", "SinkBasin", "LaundryHamper")),
    "bin": (bin_, ("GarbageCan",)),
    "appliance": (appliance, ("WashingMachine", "ClothesDryer")),
}
_BY_TYPE = {t: fam for fam, (_, types) in FAMILIES.items() for t in types}


def family_of(object_type: str) -> str:
    """The shape family of an AI2-THOR type ("block" for types without their own shape)."""
    return _BY_TYPE.get(object_type, "block")


def shape_parts(object_type: str, size: tuple[float, float, float]) -> list[Part]:
    w, h, d = (max(float(v), 1e-3) for v in size)
    fam = family_of(object_type)
    return FAMILIES[fam][0](w, h, d) if fam in FAMILIES else block(w, h, d)


_BOX_V = np.array([[x, y, z] for x in (-.5, .5) for y in (-.5, .5) for z in (-.5, .5)])
_BOX_F = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                   [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])


def _cylinder() -> tuple[np.ndarray, np.ndarray]:
    n = CYLINDER_SIDES
    a = 2 * np.pi * (np.arange(n) + 0.5) / n
    ring = np.stack([0.5 * np.cos(a), np.zeros(n), 0.5 * np.sin(a)], axis=1)
    v = np.concatenate([ring + [0, -.5, 0], ring + [0, .5, 0], [[0, -.5, 0], [0, .5, 0]]])
    f = []
    for i in range(n):
        j = (i + 1) % n
        f += [[i, n + i, n + j], [i, n + j, j], [2 * n, i, j], [2 * n + 1, n + j, n + i]]
    return v, np.array(f)


_CYL_V, _CYL_F = _cylinder()


def shape_mesh(object_type: str, size: tuple[float, float, float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(vertices (V, 3) float32, faces (F, 3) int32 wound counter-clockwise seen from outside, face
    shades (F,)) of the object's shape in its own frame."""
    verts, faces, shades, base = [], [], [], 0
    for p in shape_parts(object_type, size):
        v, f = (_BOX_V, _BOX_F) if p.kind == "box" else (_CYL_V, _CYL_F)
        verts.append(v * np.asarray(p.extents) + np.asarray(p.centre))
        faces.append(f + base)
        shades.append(np.full(len(f), p.shade))
        base += len(v)
    return (np.concatenate(verts).astype(np.float32), np.concatenate(faces).astype(np.int32),
            np.concatenate(shades))
