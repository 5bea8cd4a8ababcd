"""The nine room types of interfaces.md, their aliases, sizes and AI2-THOR names."""

from __future__ import annotations

import re
from dataclasses import dataclass

from models.errors import InputError

ROOM_TYPES: tuple[str, ...] = ("kitchen", "living room", "bedroom", "bathroom", "dining room", "office",
                               "laundry room", "garage", "hallway")


class UnknownRoomType(InputError):
    def __init__(self, given: str):
        super().__init__(f"unknown room type {given!r}; expected one of: {', '.join(ROOM_TYPES)}")


INFER = "infer"  # asked for instead of a room type: the parser infers it from the instruction


def requested_room_type(name: str | None) -> str | None:
    """A room type as the studio, the API and the CLI take it: None or `INFER` for the parser to infer it from the
    instruction, else `normalise_room_type`'s."""
    return None if name is None or name.strip().lower() == INFER else normalise_room_type(name)


def normalise_room_type(name: str) -> str:
    """`Living_Room`, `livingroom` and `living room` all read as `living room`."""
    key = re.sub(r"[\s_\-]+", "", name or "").lower()
    for room in ROOM_TYPES:
        if room.replace(" ", "") == key:
            return room
    raise UnknownRoomType(name)


@dataclass(frozen=True)
class RoomSpec:
    """Floor size range (metres), the names ProcTHOR uses for a room type, and the furniture that makes a room
    of the type what it is."""

    min_side: float
    max_side: float
    procthor_type: str  # ProcTHOR's roomType (it knows only four)
    ithor: str | None  # the iTHOR room type whose object statistics apply, if any
    # floor types every planned room of the type gets (models.planning.room_planner): each stands in every one of
    # the iTHOR rooms of the type (for the others: the authored prior's 1.0 below), and names what the room is for;
    # not the garbage can or the floor lamp, which also stand in every iTHOR room of some types
    defining: tuple[str, ...] = ()


ROOM_SPECS: dict[str, RoomSpec] = {
    "kitchen": RoomSpec(3.5, 5.5, "Kitchen", "kitchen", ("Fridge", "CounterTop")),
    "living room": RoomSpec(4.0, 6.5, "LivingRoom", "living room", ("Sofa",)),
    "bedroom": RoomSpec(3.5, 5.5, "Bedroom", "bedroom", ("Bed",)),
    "bathroom": RoomSpec(2.5, 4.0, "Bathroom", "bathroom", ("Toilet", "Sink")),
    "dining room": RoomSpec(3.5, 5.5, "LivingRoom", None, ("DiningTable",)),
    "office": RoomSpec(3.0, 5.0, "LivingRoom", None, ("Desk",)),
    "laundry room": RoomSpec(2.5, 4.0, "Bathroom", None, ("WashingMachine",)),
    "garage": RoomSpec(4.5, 7.0, "LivingRoom", None),
    "hallway": RoomSpec(2.0, 6.0, "LivingRoom", None),
}

# Floor-object priors for the five room types that iTHOR has no scenes of. These are authored by us
# (not measured): type -> chance that a room of this type has one. The four iTHOR room types use
# frequencies counted over the 120 hand-designed iTHOR rooms instead (catalogue.json, "rooms").
AUTHORED_ROOM_PRIORS: dict[str, dict[str, float]] = {
    "dining room": {"DiningTable": 1.0, "ShelvingUnit": 0.4, "HousePlant": 0.5, "FloorLamp": 0.4,
                    "SideTable": 0.3, "GarbageCan": 0.3, "Dresser": 0.2},
    "office": {"Desk": 1.0, "ShelvingUnit": 0.6, "FloorLamp": 0.4, "GarbageCan": 0.6, "HousePlant": 0.4,
               "ArmChair": 0.3, "SideTable": 0.3, "Safe": 0.2, "Sofa": 0.2},
    "laundry room": {"WashingMachine": 1.0, "ClothesDryer": 0.9, "LaundryHamper": 0.7, "ShelvingUnit": 0.5,
                     "GarbageCan": 0.4, "Sink": 0.3, "VacuumCleaner": 0.3},
    "garage": {"ShelvingUnit": 0.9, "Cart": 0.5, "GarbageCan": 0.6, "GarbageBag": 0.4, "VacuumCleaner": 0.3,
               "Stool": 0.3, "Safe": 0.2, "WashingMachine": 0.2},
    "hallway": {"SideTable": 0.6, "HousePlant": 0.5, "FloorLamp": 0.3, "ShelvingUnit": 0.3, "GarbageCan": 0.2,
                "DogBed": 0.2, "Ottoman": 0.2},
}
