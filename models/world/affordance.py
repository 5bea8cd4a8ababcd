"""How much free floor an object needs in front of it to be used (the paper's affordance clearance).

Doors that swing (fridge, safe) need their measured swing depth from the asset database plus room for
a person; furniture used from the front (counter, desk, toilet) needs a person's depth; chairs, lamps
and plants need none.
"""

from __future__ import annotations

PERSON_DEPTH = 0.5
USED_FROM_FRONT = {"CounterTop", "Sink", "Desk", "Dresser", "Toilet", "Sofa", "ArmChair", "TVStand",
                   "ShelvingUnit", "WashingMachine", "ClothesDryer", "Bed", "Safe", "Fridge", "Cart", "Television",
                   "Cabinet", "Drawer", "Shelf", "StoveBurner", "SinkBasin"}


def front_clearance(type_name: str, open_swing: float) -> float:
    """Depth in metres of the clearance rectangle in front of an object of this type."""
    if open_swing > 0.2:
        return round(max(PERSON_DEPTH, open_swing + 0.25), 3)
    return PERSON_DEPTH if type_name in USED_FROM_FRONT else 0.0
