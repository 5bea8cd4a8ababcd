"""TaskGraph -> RoomPlan: the room shell plus the task objects and context objects drawn from real priors.

Floor objects (fridge, counter, table...) go to the placer; everything that stands on or in something
(bread, microwave, desk lamp) becomes a surface object with a parent floor object, which is added
when the room has none that can hold it. Context objects are sampled from how often each type occurs
in the 120 hand-designed iTHOR rooms of that type (authored priors for the five other room types), and
furniture groups (a dining table with its chairs, a desk with its chair) follow ProcTHOR's groups; each type comes as
often as it does there (one bed in most bedrooms, two side tables in a living room on average). Deterministic for a
seed.
"""

from __future__ import annotations

import math
import random
from collections import Counter
from dataclasses import dataclass

from models.planning.shell import make_room
from models.values import PlanObject, Provenance, RoomPlan, Size, SurfaceObject, TaskGraph
from models.world import catalogue
from models.world.catalogue import Catalogue, load_json
from models.world.rooms import AUTHORED_ROOM_PRIORS, ROOM_SPECS

# Floor types that are task furniture only, never sampled as context (they'd clutter every room).
NEVER_CONTEXT = {"BaseballBat", "BasketBall", "Box", "Plunger", "Boots", "GarbageBag", "RoomDecor", "Television"}
GROUP_MEMBER_TYPES = {"Chair", "FloorLamp", "ArmChair", "Sofa"}
# Receptacles where an object starts when it must be picked up: open surfaces people reach easily.
OPEN_SURFACES = ("CounterTop", "DiningTable", "SideTable", "Desk", "CoffeeTable", "Dresser", "ShelvingUnit",
                 "Bed", "Sofa", "ArmChair", "Sink", "Toilet")
# Chairs no table or desk seats: iTHOR rooms without either hold 0.6 (living rooms), 0.57 (kitchens), 0 (bedrooms)
LONE_MEMBERS = {"Chair": 1}
# Members whose number iTHOR ties to another piece, drawn from the rooms with it (or without it) where the room type
# can have it: living rooms with a dining table hold 4.4 chairs (0-8), those without 0.75 (0-3)
SEATED_BY = {"Chair": "DiningTable"}
FLOOR_FILL_LIMIT = 0.42  # share of the floor that furniture footprints may cover


@dataclass(frozen=True)
class RoomPlannerSettings:
    """Knobs of the generator (the constraint datasets vary them to make different distributions)."""

    min_context: int = 2
    max_context: int = 8
    size_scale: float = 1.0
    surface_items: float = 0.5  # expected context items per open surface
    group_chance: float = 0.8
    # build rooms as the stored datasets were built: no defining furniture (rooms.RoomSpec.defining), and a count of
    # context pieces drawn first and filled by frequency, repeats allowed (bathrooms got 1.1 side tables, iTHOR's 0.2)
    as_stored: bool = False


def plan_role(roles: list[str]) -> str:
    for r in ("anchor", "inference", "key"):
        if r in roles:
            return r
    return "context"


class RoomPlanner:
    name = "prior-sampler"

    def __init__(self, settings: RoomPlannerSettings | None = None, cat: Catalogue | None = None):
        self.settings = settings or RoomPlannerSettings()
        self.cat = cat or catalogue()
        self.groups = load_json("asset_groups.json")

    def plan(self, graph: TaskGraph, seed: int = 0, plan_id: str | None = None) -> RoomPlan:
        structure = sorted({o.type for o in graph.objects if not self.cat.placeable(o.type)})
        if structure:
            raise ValueError(f"the task graph names part of the room's structure as an object "
                             f"({', '.join(structure)}): it has no AI2-THOR asset and cannot be placed; remove it")
        rng = random.Random(seed)
        room_type = graph.room_type
        counter: Counter[str] = Counter()
        floor: list[PlanObject] = []
        surface: list[SurfaceObject] = []

        def new_id(type_name: str) -> str:
            n = counter[type_name]
            counter[type_name] += 1
            return f"{type_name.lower()}-{n}"

        def add_floor(type_name: str, role: str) -> PlanObject:
            # sized like the type's pieces in iTHOR rooms of the type: a bathroom's counter is a vanity, not an island
            like = () if self.settings.as_stored else self.cat.ithor_footprints(type_name, room_type)
            asset = self.cat.pick_asset_like(type_name, rng, like)
            obj = PlanObject(id=new_id(type_name), type=type_name, size=Size(x=asset.size[0], y=asset.size[1],
                                                                              z=asset.size[2]), role=role)
            floor.append(obj)
            return obj

        # 1. task objects
        pending: list[tuple[str, str]] = []
        for task_obj in graph.objects:
            role = plan_role(task_obj.roles)
            if self.cat.is_floor_object(task_obj.type) and not self.cat.host(task_obj.type).pickupable:
                add_floor(task_obj.type, role)
            else:
                pending.append((task_obj.type, role))
        anchor_ids = {o.id for o in floor if o.role == "anchor"}

        # 2. the furniture that makes the room its type (a bedroom's bed) unless the task brought it, then context
        # furniture from the room priors, then the groups they anchor
        if self.settings.as_stored:
            keep, context, members = set(), self._sample_context(room_type, rng, {o.type for o in floor}), []
        else:
            brought = {o.type for o in floor}
            keep = {add_floor(t, "context").id for t in ROOM_SPECS[room_type].defining if t not in brought}
            drawn = self._draw_context(room_type, rng, Counter(o.type for o in floor))
            context = [t for t in drawn if t not in GROUP_MEMBER_TYPES]
            members = [t for t in drawn if t in GROUP_MEMBER_TYPES]  # furnish the groups first, the rest after
        for type_name in context:
            add_floor(type_name, "context")
        grouped: Counter[str] = Counter()
        budget = Counter(members) if ROOM_SPECS[room_type].ithor and not self.settings.as_stored else None
        for root in list(floor):
            for member in self._group_members(root.type, room_type, rng, budget):
                grouped[add_floor(member, "context").type] += 1
        alone: Counter[str] = Counter()
        for type_name in members:
            if grouped[type_name]:
                grouped[type_name] -= 1
            elif type_name not in LONE_MEMBERS or alone[type_name] < LONE_MEMBERS[type_name]:
                alone[type_name] += 1
                add_floor(type_name, "context")

        # 3. surface objects: task objects first (the manipulated one away from its destination)
        target = graph.target
        for type_name, role in pending:
            avoid = anchor_ids if type_name == target else set()
            parent = self._parent_for(type_name, floor, avoid, rng) or add_floor(self._host_type_for(type_name,
                                                                                                      room_type), "context")
            surface.append(self._surface(type_name, role, parent.id, new_id, rng))
        for obj in list(floor):
            if obj.type in OPEN_SURFACES and rng.random() < self.settings.surface_items:
                child = self._sample_child(obj.type, room_type, rng)
                if child:
                    surface.append(self._surface(child, "context", obj.id, new_id, rng))

        floor = self._fit_floor(floor, surface, room_type, keep)
        min_area = sum(o.size.x * o.size.z for o in floor) / FLOOR_FILL_LIMIT
        room = make_room(room_type, rng, min_area=min_area, size_scale=self.settings.size_scale)
        if len(room.doors) > 1 and not self.settings.as_stored:  # the robot enters by one door: keep the others joined
            room = room.model_copy(update={"crossed": True})
        kept = {o.id for o in floor}
        surface = [s for s in surface if s.parent in kept]
        return RoomPlan(id=plan_id or f"plan-{seed}", room=room, objects=floor, surface_objects=surface,
                        provenance=Provenance(stage="room_plan", method=self.name, seed=seed))

    # ---- selection helpers -----------------------------------------------------------------------

    def _candidates(self, room_type: str) -> dict[str, float]:
        if ROOM_SPECS[room_type].ithor is None:
            return dict(AUTHORED_ROOM_PRIORS[room_type])
        out = {}
        for name, t in self.cat.types.items():
            if t.on_floor and not t.pickupable and name not in NEVER_CONTEXT and t.assets:
                p = self.cat.room_presence(name, room_type)
                if p > 0.05:
                    out[name] = p
        return out

    def _draw_context(self, room_type: str, rng: random.Random, present: Counter[str]) -> list[str]:
        """Each candidate type with its chance of being in such a room, then as many of it as such rooms hold (1 plus
        a Poisson draw with the iTHOR mean's excess), less those already there; chairs after the dining table, by
        the rooms with or without one. At most max_context pieces besides the chairs, lamps, armchairs and sofas
        (which groups seat; as many as drawn), the first of each type before any second; topped up by frequency
        below min_context."""
        weights = self._candidates(room_type)
        tied = [n for n in sorted(weights) if SEATED_BY.get(n) in weights]  # drawn once their root's draw is known
        drawn: list[tuple[int, float, str]] = []
        for name in [n for n in sorted(weights) if n not in tied] + tied:
            chance, count = weights[name], self.cat.room_count(name, room_type)
            if name in tied:
                root = SEATED_BY[name]
                chance, count = self.cat.room_stats_given(name, room_type, root,
                                                          bool(present[root]) or any(n == root for *_, n in drawn))
            if rng.random() >= chance:
                continue
            extra = _poisson(count - 1, rng) if self._repeats(name) else 0
            drawn += [(k, rng.random(), name) for k in range(present[name], 1 + extra)]
        ordered = [name for _, _, name in sorted(drawn)]
        chosen = [n for n in ordered if n not in GROUP_MEMBER_TYPES][:self.settings.max_context]
        chosen += [n for n in ordered if n in GROUP_MEMBER_TYPES]
        short = self.settings.min_context - len(chosen)
        return chosen + self._fill(room_type, rng, set(present) | set(chosen), short)

    def _repeats(self, name: str) -> bool:
        return bool(self.cat[name].placement.get("multiple_per_room"))

    def _sample_context(self, room_type: str, rng: random.Random, present: set[str]) -> list[str]:
        """As the stored datasets were built: a count drawn from [min_context, max_context], filled by `_fill`."""
        s = self.settings
        return self._fill(room_type, rng, present, rng.randint(s.min_context, s.max_context))

    def _fill(self, room_type: str, rng: random.Random, present: set[str], count: int) -> list[str]:
        """`count` types drawn by room frequency. Types that occur once per room (a fridge) are drawn at most once
        and not when `present`; others may repeat."""
        weights = self._candidates(room_type)
        chosen: list[str] = []
        names = sorted(weights)
        while len(chosen) < count:
            options = [n for n in names if self._repeats(n) or (n not in chosen and n not in present)]
            if not options:
                break
            chosen.append(rng.choices(options, weights=[weights[n] for n in options])[0])
        return chosen

    def _group_members(self, root: str, room_type: str, rng: random.Random,
                       budget: Counter[str] | None = None) -> list[str]:
        """The chairs, lamps... of a ProcTHOR group anchored by `root`, or none. With a `budget` (the members drawn
        for the room, used up here), the largest group it furnishes, so that a kitchen's table does not bring six
        chairs where iTHOR kitchens hold 0.7; without, any group of the room type."""
        ithor_key = {"kitchen": "kitchens", "living room": "livingRooms", "bedroom": "bedrooms",
                     "bathroom": "bathrooms"}.get(room_type)
        options = [g for g in self.groups.values() if g["members"][0]["type"] == root
                   and (ithor_key is None or g["room_weights"].get(ithor_key, 0) > 0)
                   and any(m["type"] in GROUP_MEMBER_TYPES for m in g["members"][1:])]
        seated = budget is not None and root in SEATED_BY.values()  # its chairs were drawn for it: no second roll
        if not options or (not seated and rng.random() > self.settings.group_chance):
            return []
        if budget is None:
            return _members(rng.choice(sorted(options, key=lambda g: len(g["members"]))))
        fitting = [_members(g) for g in options if not Counter(_members(g)) - budget]
        if not fitting:
            return []
        largest = max(len(m) for m in fitting)
        chosen = rng.choice(sorted(m for m in fitting if len(m) == largest))
        budget.subtract(chosen)
        return chosen

    def _accepts(self, parent_type: str, child: str) -> float:
        return self.cat.host(parent_type).contents.get(child, 0.0)

    def _parent_for(self, child: str, floor: list[PlanObject], avoid: set[str],
                    rng: random.Random) -> PlanObject | None:
        scored = [(self._accepts(o.type, child), o) for o in floor if o.id not in avoid]
        scored = [(p, o) for p, o in scored if p > 0]
        if not scored:
            return None
        best = max(p for p, _ in scored)
        return rng.choice([o for p, o in scored if p == best])

    def _host_type_for(self, child: str, room_type: str) -> str:
        """The floor receptacle that most often holds `child`, weighted by how common it is in the room."""
        options = [n for n, t in self.cat.types.items() if t.on_floor and not t.pickupable and t.assets
                   and t.contents.get(child, 0) > 0]
        if not options:
            return "CounterTop" if room_type == "kitchen" else "SideTable"
        return max(options, key=lambda n: (self.cat[n].contents[child] * (0.1 + self.cat.room_presence(n, room_type)), n))

    def _sample_child(self, parent: str, room_type: str, rng: random.Random) -> str | None:
        contents = {c: p * (0.05 + self.cat.room_presence(c, room_type))
                    for c, p in self.cat.host(parent).contents.items()
                    if c in self.cat and self.cat[c].pickupable and self.cat[c].assets}
        if not contents:
            return None
        names = sorted(contents)
        return rng.choices(names, weights=[contents[n] for n in names])[0]

    def _surface(self, type_name: str, role: str, parent: str, new_id, rng: random.Random) -> SurfaceObject:
        asset = self.cat.pick_asset(type_name, rng)
        return SurfaceObject(id=new_id(type_name), type=type_name, role=role, parent=parent,
                             size=Size(x=asset.size[0], y=asset.size[1], z=asset.size[2]))

    def _fit_floor(self, floor: list[PlanObject], surface: list[SurfaceObject], room_type: str,
                   keep: set[str]) -> list[PlanObject]:
        """Drop context furniture (the largest first; never `keep`) while it would cover too much of the largest
        room."""
        spec = ROOM_SPECS[room_type]
        largest = (spec.max_side * self.settings.size_scale) ** 2
        needed = keep | {s.parent for s in surface if s.role != "context"}
        floor = list(floor)
        while sum(o.size.x * o.size.z for o in floor) > FLOOR_FILL_LIMIT * largest:
            droppable = [o for o in floor if o.role == "context" and o.id not in needed]
            if not droppable:
                break
            floor.remove(max(droppable, key=lambda o: o.size.x * o.size.z))
        return floor


def _members(group: dict) -> list[str]:
    return [m["type"].split("-")[0] for m in group["members"][1:] if m["type"].split("-")[0] in GROUP_MEMBER_TYPES]


def _poisson(mean: float, rng: random.Random) -> int:
    """A Poisson draw (Knuth's product of uniforms); 0 for a mean of 0 or less."""
    k, product, floor = 0, rng.random(), math.exp(-max(mean, 0.0))
    while product > floor:
        k += 1
        product *= rng.random()
    return k
