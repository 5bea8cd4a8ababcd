"""TaskGraph -> HousePlan: which rooms, which task object goes to which room, each room planned, one floorplan.

Task objects go to the room type where iTHOR's hand-built rooms have them most often (the task's own room
type, as the parser read or inferred it, wins a near tie): the fridge and the counter to the kitchen, the
bed to the bedroom. A surface object no listed room has (a microwave asked for in an office) stays in the
task's room, or else the anchor's. Each room is then planned by the single-room RoomPlanner (context
objects from that room type's priors) and the rooms, sized by what they hold, are laid out by a
FloorplanMaker. Deterministic for a seed.
"""

from __future__ import annotations

import random
import re

from models.errors import InputError
from models.planning.floorplan import FloorplanMaker, SlicingFloorplan
from models.planning.room_planner import RoomPlanner
from models.values import RoomPlan, TaskGraph
from models.values.apartment import APARTMENT, HousePlan
from models.world import ROOM_TYPES, UnknownRoomType, catalogue, normalise_room_type

MAX_ROOMS = 8
HOME_BONUS = 0.25  # the task's own room type wins when another type is at most this much more likely
FILL_ORDER = ("bathroom", "bedroom", "kitchen", "dining room", "office", "bedroom")


class ApartmentError(InputError):
    """A room list or task that cannot make an apartment (one line, for the CLI and the API)."""


def is_apartment(room_type: str | None) -> bool:
    return re.sub(r"[\s_\-]+", "", room_type or "").lower() == APARTMENT


def parse_rooms(rooms: str | list[str] | None) -> list[str] | None:
    """`"kitchen, living room, bedroom"` -> normalised room types; None when not given."""
    if rooms is None:
        return None
    names = [r.strip() for r in (rooms.split(",") if isinstance(rooms, str) else rooms) if r.strip()]
    if not names:
        raise ApartmentError("--rooms is empty; list room types separated by commas, e.g. 'kitchen, bedroom'")
    if len(names) > MAX_ROOMS:
        raise ApartmentError(f"an apartment has at most {MAX_ROOMS} rooms; {len(names)} were given")
    try:
        return [normalise_room_type(n) for n in names]
    except UnknownRoomType as e:
        raise ApartmentError(f"in the room list: {e}") from e


def _presence(type_name: str, room_type: str) -> float:
    cat = catalogue()
    return cat.room_presence(type_name, room_type) if type_name in cat else 0.0


def _best_room(type_name: str, rooms: list[str], home: str) -> int | None:
    """Index of the room where the type is most likely (the home type preferred); None if in none."""
    scores = [_presence(type_name, r) + (HOME_BONUS if r == home else 0.0) * (_presence(type_name, r) > 0)
              for r in rooms]
    best = max(scores)
    return scores.index(best) if best > 0 else None


def _is_furniture(type_name: str) -> bool:
    cat = catalogue()
    return type_name in cat and cat.is_floor_object(type_name) and not cat.host(type_name).pickupable


def assign_objects(graph: TaskGraph, rooms: list[str]) -> dict[str, int]:
    """Task object type -> index of its room; ApartmentError when furniture the task needs fits no room."""
    home = graph.room_type
    out: dict[str, int] = {}
    for obj in sorted(graph.objects, key=lambda o: not _is_furniture(o.type)):
        best = _best_room(obj.type, rooms, home)
        if best is None and _is_furniture(obj.type):
            usual = max(ROOM_TYPES, key=lambda r: _presence(obj.type, r))
            raise ApartmentError(f"none of the rooms ({', '.join(rooms)}) holds a {obj.type} in the priors; "
                                 f"add a {usual} to the rooms")
        if best is None:
            anchor = graph.anchor.type if graph.anchor else None
            best = rooms.index(home) if home in rooms else out.get(anchor, 0)
        out[obj.type] = best
    return out


def choose_rooms(graph: TaskGraph, rng: random.Random) -> list[str]:
    """2-5 rooms: those the task's objects belong to, a living room, then a seeded fill."""
    pool = ["kitchen", "living room", "bedroom", "bathroom"]
    pool += [graph.room_type] if graph.room_type not in pool else []
    needed = [graph.room_type] + [pool[_best_room(o.type, pool, graph.room_type) or 0] for o in graph.objects]
    rooms = list(dict.fromkeys(needed + ["living room"]))
    target = rng.randint(max(2, len(rooms)), max(5, len(rooms)))
    fill = list(FILL_ORDER)
    rng.shuffle(fill)
    for r in fill:
        if len(rooms) >= target:
            break
        if rooms.count(r) < FILL_ORDER.count(r):
            rooms.append(r)
    return rooms[:MAX_ROOMS]


def _prefixed(plan: RoomPlan, prefix: str) -> RoomPlan:
    """The plan with every object id prefixed, so that ids are unique across the apartment."""
    objects = [o.model_copy(update={"id": prefix + o.id}) for o in plan.objects]
    surface = [s.model_copy(update={"id": prefix + s.id, "parent": prefix + s.parent}) for s in plan.surface_objects]
    return plan.model_copy(update={"objects": objects, "surface_objects": surface})


class ApartmentPlanner:
    name = "apartment"

    def __init__(self, planner: RoomPlanner | None = None, floorplan: FloorplanMaker | None = None):
        self.planner = planner or RoomPlanner()
        self.floorplan = floorplan or SlicingFloorplan()

    def plan(self, graph: TaskGraph, rooms: list[str] | None = None, seed: int = 0,
             plan_id: str | None = None) -> HousePlan:
        """`graph.room_type` is the task's own room type (not "apartment")."""
        rooms = rooms or choose_rooms(graph, random.Random(seed))
        where = assign_objects(graph, rooms)
        plans = []
        for i, room_type in enumerate(rooms):
            objects = [o for o in graph.objects if where[o.type] == i]
            sub = graph.model_copy(update={"room_type": room_type, "objects": objects})
            plan = self.planner.plan(sub, seed=seed * 1000 + i, plan_id=f"{plan_id or f'plan-{seed}'}-room-{i + 1}")
            plans.append(_prefixed(plan, f"r{i + 1}-"))
        floorplan = self.floorplan.make([p.room for p in plans], seed)
        room_plans = [p.model_copy(update={"room": hr.room}) for p, hr in zip(plans, floorplan.rooms)]
        return HousePlan(id=plan_id or f"plan-{seed}", floorplan=floorplan, room_plans=room_plans,
                         assignment={o.type: floorplan.rooms[where[o.type]].id for o in graph.objects})
