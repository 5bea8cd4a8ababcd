"""An object carried from one room of an apartment to another (a designer's drag onto another room's floor).

The object goes with what stands on it. It takes the destination room's id prefix (`r2-armchair-0` -> `r3-armchair-0`,
the next free number if that is taken), since an apartment's ids say which room holds them. The source room's
constraint text loses the object's line and every constraint that targets it; the destination's gets a line with
the object's own `edge` / `middle`. A task object's room in the house plan follows it, so the robot's visits, the
VR user's room and Key_NAV are measured again when the apartment is assembled.
"""

from __future__ import annotations

import re

from models.constraints.holodeck_text import without_object
from models.placement.problem import plan_constraints
from models.scene.apartment import assemble_apartment
from models.values import Placement, RoomPlan
from models.values.apartment import Apartment


def room_holding(apartment: Apartment, object_id: str) -> int:
    """The index (floorplan order) of the room whose plan holds `object_id`."""
    for k, plan in enumerate(apartment.plans):
        if any(o.id == object_id for o in plan.objects):
            return k
    raise ValueError(f"{object_id} is not a floor object of apartment {apartment.id}")


def _free_id(object_id: str, prefix: str, taken: set[str]) -> str:
    """`object_id` under the room prefix `prefix`, its number raised until it is not `taken`."""
    name = prefix + object_id.split("-", 1)[1]
    stem, number = re.fullmatch(r"(.*?)-?(\d*)", name).groups()
    n = int(number or 0)
    while name in taken:
        n += 1
        name = f"{stem}-{n}"
    return name


def carry(apartment: Apartment, object_id: str, to: int, x: float, z: float, rotation: float,
          seed: int = 0) -> tuple[Apartment, str]:
    """(the apartment with `object_id` in room `to` at (x, z, rotation) in that room's frame, the object's new id)."""
    k = room_holding(apartment, object_id)
    if not 0 <= to < len(apartment.plans) or to == k:
        raise ValueError(f"carry {object_id} from room {k + 1} to another of rooms 1-{len(apartment.plans)}, "
                         f"not {to + 1}")
    placed = apartment.layouts[k].placement(object_id)
    if placed is None:
        raise ValueError(f"{object_id} was left out of room {k + 1}'s layout: there is nothing to carry")
    source_rp, dest_rp = apartment.plan.room_plans[k], apartment.plan.room_plans[to]
    prefix = f"r{apartment.floorplan.rooms[to].id.split('|')[-1]}-"
    taken = {o.id for o in dest_rp.objects} | {s.id for s in dest_rp.surface_objects}
    new_id = _free_id(object_id, prefix, taken)
    riders = [s for s in source_rp.surface_objects if s.parent == object_id]
    moved_riders = []
    for s in riders:
        moved_riders.append(s.model_copy(update={"id": _free_id(s.id, prefix, taken | {new_id}), "parent": new_id}))
        taken.add(moved_riders[-1].id)
    obj = next(o for o in source_rp.objects if o.id == object_id).model_copy(update={"id": new_id, "holds": None})
    room_plans = list(apartment.plan.room_plans)
    room_plans[k] = source_rp.model_copy(update={
        "objects": [o for o in source_rp.objects if o.id != object_id],
        "surface_objects": [s for s in source_rp.surface_objects if s.parent != object_id]})
    dumped = dest_rp.model_dump()  # validated again, so that `holds` marks what the object carries
    room_plans[to] = RoomPlan.model_validate({**dumped, "objects": [*dumped["objects"], obj.model_dump()],
                                              "surface_objects": [*dumped["surface_objects"],
                                                                  *(r.model_dump() for r in moved_riders)]})
    arrived = next(o for o in room_plans[to].objects if o.id == new_id)

    source, dest = apartment.plans[k], apartment.plans[to]
    placement = plan_constraints(source).objects[object_id].placement
    plans = list(apartment.plans)
    plans[k] = source.model_copy(update={"objects": [o for o in source.objects if o.id != object_id],
                                         "constraints": without_object(source.constraints, object_id)})
    plans[to] = dest.model_copy(update={"objects": [*dest.objects, arrived], "constraints": "\n".join(
        line for line in (dest.constraints, f"{new_id} | {placement}") if line)})
    layouts = list(apartment.layouts)
    layouts[k] = layouts[k].model_copy(update={"placements": [p for p in layouts[k].placements if p.id != object_id]})
    layouts[to] = layouts[to].model_copy(update={"placements": [*layouts[to].placements, Placement(
        id=new_id, type=placed.type, x=round(x, 4), z=round(z, 4), rotation=rotation % 360, size=placed.size)]})

    going = {o.type for o in [obj, *riders] if o.role != "context"}
    rooms = apartment.floorplan.rooms
    assignment = {t: rooms[to].id if t in going and r == rooms[k].id else r
                  for t, r in apartment.plan.assignment.items()}
    house = apartment.plan.model_copy(update={"room_plans": room_plans, "assignment": assignment})
    return assemble_apartment(house, plans, layouts, apartment.task_graph, seed), new_id
