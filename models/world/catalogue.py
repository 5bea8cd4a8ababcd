"""The catalogue of AI2-THOR object types, loaded from the bundled `models/data/catalogue.json`."""

from __future__ import annotations

import gzip
import json
import random
import statistics
from dataclasses import dataclass, field
from functools import cache, cached_property
from importlib import resources

from models.world.affordance import front_clearance
from models.world.lexicon import build_lexicon
from models.world.rooms import AUTHORED_ROOM_PRIORS, ROOM_SPECS

# Types that are parts of a larger fixture in iTHOR and have no ProcTHOR asset of their own: they are
# placed and exported as the asset of their host (an AI2-THOR counter carries its cabinets and
# burners), and the scene says so in its warnings.
HOST_TYPES: dict[str, str] = {
    "Cabinet": "CounterTop", "StoveBurner": "CounterTop", "SinkBasin": "Sink", "BathtubBasin": "Sink",
    "Drawer": "Dresser", "Shelf": "ShelvingUnit", "Bathtub": "Sink", "StoveKnob": "CounterTop",
}

# Types that stand free in the room whatever their wall prior says (they are arranged around others).
MIDDLE_TYPES = {"Chair", "Stool", "CoffeeTable", "Ottoman", "Cart"}
LAMPS = ("DeskLamp", "FloorLamp")  # the lamps of ALFRED's look-at tasks

# Footprints are modelled as rectangles, so L- and C-shaped counters (whose bounding box is mostly
# empty) are not offered: only the straight ("I") and island counters are.
RECTANGULAR_ONLY: dict[str, tuple[str, ...]] = {"CounterTop": ("Countertop_I_", "Countertop_Island_")}


@dataclass(frozen=True)
class Asset:
    asset_id: str
    size: tuple[float, float, float]  # x (width), y (height), z (depth), metres
    split: str | None


@dataclass(frozen=True)
class ObjectType:
    """One AI2-THOR object type with its assets, physical properties and placement priors."""

    name: str
    assets: tuple[Asset, ...]
    flags: dict[str, bool]
    mass: float
    size: tuple[float, float, float]
    materials: tuple[str, ...]
    placement: dict[str, bool | None]
    rooms: dict[str, dict[str, float]]
    contents: dict[str, float] = field(default_factory=dict)
    open_swing: float = 0.0  # how much deeper the asset gets when opened (fridge and cabinet doors), metres

    @property
    def pickupable(self) -> bool:
        return self.flags["pickupable"]

    @property
    def on_floor(self) -> bool:
        return bool(self.placement.get("on_floor"))

    @property
    def against_wall(self) -> bool:
        """The prior says it usually stands against a wall (edge or corner) rather than in the middle."""
        p = self.placement
        return bool(p.get("on_edge") or p.get("in_corner")) and not p.get("in_middle")


class Catalogue:
    """All object types, the synonym lexicon, and per-room priors."""

    def __init__(self, raw: dict[str, dict]):
        self.types: dict[str, ObjectType] = {
            name: ObjectType(
                name=name,
                assets=tuple(Asset(a[0], (a[1], a[2], a[3]), a[4]) for a in entry["assets"]
                             if a[0].startswith(RECTANGULAR_ONLY.get(name, ("",)))),
                flags=entry["flags"], mass=entry["mass"], size=tuple(entry["size"]),
                materials=tuple(entry["materials"]), placement=entry["placement"], rooms=entry["rooms"],
                contents=entry["contents"], open_swing=entry.get("open_swing", 0.0),
            )
            for name, entry in raw.items()
        }

    def __contains__(self, name: str) -> bool:
        return name in self.types

    def __getitem__(self, name: str) -> ObjectType:
        return self.types[name]

    @cached_property
    def lexicon(self) -> dict[str, tuple[str, ...]]:
        return build_lexicon(sorted(self.types))

    def host(self, name: str) -> ObjectType:
        """The type whose asset stands for `name` (itself unless it is a fixture part)."""
        return self.types[HOST_TYPES.get(name, name)]

    def default_placement(self, name: str) -> str:
        """`edge` or `middle`: the global placement an object gets when its plan line says nothing."""
        if name in MIDDLE_TYPES:
            return "middle"
        return "edge" if self.host(name).against_wall else "middle"

    def front_clearance(self, name: str) -> float:
        host = self.host(name)
        return front_clearance(name if name in self.types else host.name, host.open_swing)

    def is_floor_object(self, name: str) -> bool:
        return self.host(name).on_floor

    def placeable(self, name: str) -> bool:
        """The type has a real asset (its own or its host's): not part of the room's structure (the floor,
        a mirror, curtains), which no planner can place."""
        return bool(self.host(name).assets)

    def object_type(self, name: str) -> str:
        """The placeable AI2-THOR type a designer means by `name` (a type or a common name); ValueError naming
        the problem otherwise: an unknown word, or a part of the room's structure."""
        found = self.lexicon.get(name.strip().lower(), (name.strip(),) if name.strip() in self else ())
        if not found:
            raise ValueError(f"unknown object type {name!r}: use an AI2-THOR type or a common name (fridge, sofa...)")
        if not self.placeable(found[0]):
            raise ValueError(f"{found[0]} is part of the room's structure (no AI2-THOR asset): it cannot be "
                             "added or placed as an object")
        return found[0]

    def pick_asset(self, name: str, rng: random.Random, fits: tuple[float, float] | None = None) -> Asset:
        """A real asset of the type (or its host); with `fits`, the one whose footprint is closest to it."""
        assets = self.host(name).assets
        if not assets:
            raise KeyError(f"no AI2-THOR asset for {name}")
        if fits is None:
            return rng.choice(assets)
        return min(assets, key=lambda a: abs(a.size[0] - fits[0]) + abs(a.size[2] - fits[1]) + 1e-6 * len(a.asset_id))

    def room_presence(self, name: str, room_type: str) -> float:
        """Chance that a room of this type contains the type: measured in iTHOR where possible, else authored."""
        spec = ROOM_SPECS[room_type]
        if spec.ithor is not None:
            return self.host(name).rooms.get(spec.ithor, {}).get("presence", 0.0)
        return AUTHORED_ROOM_PRIORS[room_type].get(name, 0.0)

    def room_count(self, name: str, room_type: str) -> float:
        """How many of the type a room of this type holds when it holds any: the iTHOR mean where measured, else 1."""
        spec = ROOM_SPECS[room_type]
        if spec.ithor is not None:
            return self.host(name).rooms.get(spec.ithor, {}).get("mean_count", 1.0)
        return 1.0

    def ithor_footprints(self, name: str, room_type: str) -> tuple[tuple[float, float], ...]:
        """The footprints (longer side, shorter side, metres) of the type's pieces in the iTHOR rooms of this type;
        none where iTHOR has no room of the type."""
        spec = ROOM_SPECS[room_type]
        return _footprints(spec.ithor, name) if spec.ithor is not None else ()

    def pick_asset_like(self, name: str, rng: random.Random, footprints: tuple[tuple[float, float], ...]) -> Asset:
        """A real asset of the type sized like one of `footprints` drawn at random (the asset nearest it, turned
        either way); any asset when there are none."""
        if not footprints:
            return self.pick_asset(name, rng)
        long, short = rng.choice(footprints)
        return min(self.host(name).assets, key=lambda a: (abs(max(a.size[0], a.size[2]) - long)
                                                           + abs(min(a.size[0], a.size[2]) - short), a.asset_id))

    def room_stats_given(self, name: str, room_type: str, other: str, with_other: bool) -> tuple[float, float]:
        """`room_presence` and `room_count` of the type among the iTHOR rooms of this type that hold `other` (or,
        `with_other` False, that do not): chairs come with a dining table. The plain figures where iTHOR has no
        such room."""
        spec = ROOM_SPECS[room_type]
        found = _stats_given(spec.ithor, name, other, with_other) if spec.ithor is not None else None
        return found or (self.room_presence(name, room_type), self.room_count(name, room_type))


@cache
def catalogue() -> Catalogue:
    """The bundled catalogue (loaded once per process)."""
    text = resources.files("models").joinpath("data/catalogue.json").read_text()
    return Catalogue(json.loads(text))


def ithor_scenes() -> list[dict]:
    """The 120 hand-designed iTHOR rooms: each room's type and its objects' types, poses and sizes."""
    raw = resources.files("models").joinpath("data/ithor_scenes.jsonl.gz").read_bytes()
    return [json.loads(line) for line in gzip.decompress(raw).decode().splitlines() if line]


@cache
def _ithor_rooms() -> dict[str, tuple[tuple[tuple[str, float, float], ...], ...]]:
    """Room type -> each iTHOR room of the type as its objects' (type, longer side, shorter side), read once."""
    rooms: dict[str, list] = {}
    for s in ithor_scenes():
        rooms.setdefault(s["room_type"], []).append(tuple(
            (o["type"], max(o["size"][0], o["size"][2]), min(o["size"][0], o["size"][2])) for o in s["objects"]))
    return {room_type: tuple(objs) for room_type, objs in rooms.items()}


@cache
def _footprints(room_type: str, name: str) -> tuple[tuple[float, float], ...]:
    return tuple((long, short) for objs in _ithor_rooms().get(room_type, ()) for t, long, short in objs if t == name)


@cache
def _stats_given(room_type: str, name: str, other: str, with_other: bool) -> tuple[float, float] | None:
    counts = [sum(t == name for t, _, _ in objs) for objs in _ithor_rooms().get(room_type, ())
              if any(t == other for t, _, _ in objs) == with_other]
    holding = [n for n in counts if n]
    return (round(len(holding) / len(counts), 3), round(statistics.mean(holding), 3) if holding else 1.0) \
        if counts else None


def load_json(name: str):
    """A bundled data file from `models/data`."""
    return json.loads(resources.files("models").joinpath(f"data/{name}").read_text())
