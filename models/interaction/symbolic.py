"""A symbolic AI2-THOR: the exported house's objects with their states, the robot's pose and hand, and the
effect of each action, with ALFRED's state tracking.

Rules (those of AI2-THOR's actions as far as a plan can break them): one object in hand; an object inside a
closed receptacle cannot be taken and nothing can be put into a closed one; a microwave turns on only when
closed, and opening it turns it off; SliceObject needs a knife in hand and makes a slice
(`<id>|<Type>Sliced_1`, `EggCracked_0` for an egg, as AI2-THOR names them); every interaction needs the
robot within INTERACT_RANGE of the object (AI2-THOR's default visibilityDistance); TeleportFull must land
on free floor connected to the robot's start (a robot of models.energy.weights.ROBOT_RADIUS). In a house of
several rooms the floor is each room's, away from its walls, joined only through the doorways between
rooms (models.interaction.floors), and the robot acts only on objects in the room it stands in.
State tracking as ALFRED's: after every step, whatever is inside a closed cold source (the fridge) is
cooled, and whatever is inside a heat source that is on (the microwave) is heated.
"""

from __future__ import annotations

from functools import cache
from typing import Any

import numpy as np
import shapely
import shapely.affinity
from pydantic import BaseModel, ConfigDict, PrivateAttr
from scipy import ndimage
from shapely.geometry import Point

from models.energy import navigation as nav
from models.energy.weights import ROBOT_RADIUS
from models.geometry import Footprint
from models.interaction.floors import Passage, floors, passages, room_cells, walkable
from models.values.interaction import PlanStep, StepResult
from models.world import catalogue

INTERACT_RANGE = 1.5
KNIVES = frozenset({"Knife", "ButterKnife"})
OBJECT_ACTIONS = ("OpenObject", "CloseObject", "PickupObject", "PutObject", "ToggleObjectOn", "ToggleObjectOff",
                  "SliceObject")


@cache
def asset_sizes() -> dict[str, tuple[float, float, float]]:
    """Every catalogued asset's (width, height, depth)."""
    return {a.asset_id: a.size for t in catalogue().types.values() for a in t.assets}


def slice_id(object_id: str, type_name: str) -> str:
    return f"{object_id}|EggCracked_0" if type_name == "Egg" else f"{object_id}|{type_name}Sliced_1"


class ObjectState(BaseModel):
    model_config = ConfigDict(extra="forbid")

    id: str
    type: str
    x: float
    y: float
    z: float
    rotation: float = 0.0
    width: float = 0.1
    depth: float = 0.1
    parent: str | None = None  # the receptacle it is in or on
    on_floor: bool = False
    pickupable: bool = False
    receptacle: bool = False
    openable: bool = False
    toggleable: bool = False
    sliceable: bool = False
    cold_source: bool = False
    heat_source: bool = False
    is_open: bool = False
    is_on: bool = False
    cooled: bool = False
    heated: bool = False
    sliced: bool = False  # this object was cut (it is gone; its slices exist)
    picked: bool = False  # the robot has picked it up at least once

    def footprint(self) -> Footprint:
        return Footprint(self.x, self.z, self.width, self.depth, self.rotation)


def _type_of(house_id: str) -> str:
    return house_id.split("|", 1)[0]


def _object_state(entry: dict, parent: str | None) -> ObjectState:
    type_name = _type_of(entry["id"])
    cat = catalogue()
    flags = cat[type_name].flags if type_name in cat else {}  # its own flags: a SinkBasin is a receptacle
    size = asset_sizes().get(entry.get("assetId", ""), (0.1, 0.1, 0.1))
    p, r = entry["position"], entry.get("rotation", {}).get("y", 0.0)
    return ObjectState(id=entry["id"], type=type_name, x=p["x"], y=p["y"], z=p["z"], rotation=r, width=size[0],
                       depth=size[2], parent=parent, on_floor=parent is None,
                       **{k: bool(flags.get(f)) for k, f in (
                           ("pickupable", "pickupable"), ("receptacle", "receptacle"), ("openable", "openable"),
                           ("toggleable", "toggleable"), ("sliceable", "sliceable"),
                           ("cold_source", "isColdSource"), ("heat_source", "isHeatSource"))})


class SymbolicState(BaseModel):
    """The house's objects and the robot; `execute_step` returns a new state (this one is not changed)."""

    model_config = ConfigDict(extra="forbid")

    objects: dict[str, ObjectState]
    agent_x: float
    agent_z: float
    agent_y: float = 0.95
    rotation: float = 0.0
    horizon: float = 30.0
    held: str | None = None
    room: tuple[float, float, float, float]  # xmin, zmin, xmax, zmax of the house
    floors: dict[str, list[tuple[float, float]]] = {}  # room id -> floor polygon; none: the whole box is floor
    doorways: list[Passage] = []  # between rooms: the only way from one room's floor to another's
    _reachable: Any = PrivateAttr(default=None)
    _grid: Any = PrivateAttr(default=None)
    _rooms: Any = PrivateAttr(default=None)  # per cell, the index of its room in `floors` (-1: none)

    @classmethod
    def from_house(cls, house: dict) -> SymbolicState:
        objects: dict[str, ObjectState] = {}
        for entry in house.get("objects", []):
            objects[entry["id"]] = _object_state(entry, None)
            for child in entry.get("children", []):
                objects[child["id"]] = _object_state(child, entry["id"])
        floor = [(v["x"], v["z"]) for r in house.get("rooms", []) for v in r["floorPolygon"]]
        xs, zs = zip(*floor) if floor else ((0.0, 1.0), (0.0, 1.0))
        agent = house.get("metadata", {}).get("agent", {})
        pos = agent.get("position", {"x": (min(xs) + max(xs)) / 2, "y": 0.95, "z": (min(zs) + max(zs)) / 2})
        state = cls(objects=objects, agent_x=pos["x"], agent_z=pos["z"], agent_y=pos.get("y", 0.95),
                    rotation=agent.get("rotation", {}).get("y", 0.0), horizon=agent.get("horizon", 30.0),
                    room=(min(xs), min(zs), max(xs), max(zs)), floors=floors(house), doorways=passages(house))
        state._build_navigation()
        return state

    # ---- navigation ------------------------------------------------------------------------------
    def _build_navigation(self) -> None:
        x0, z0, x1, z1 = self.room
        grid = nav.Grid(x1 - x0, z1 - z0)
        polys = [shapely.affinity.translate(o.footprint().polygon(), -x0, -z0)
                 for o in self.objects.values() if o.on_floor]
        blocked = nav.blocked_by_polygons(grid, polys)
        if self.floors:
            blocked |= ~walkable(grid, (x0, z0), self.floors, self.doorways, ROBOT_RADIUS)
            self._rooms = room_cells(grid, (x0, z0), self.floors)
        labels, _ = ndimage.label(~blocked)
        i, j = self._cell(grid, self.agent_x, self.agent_z)
        start = labels[i, j]
        if start == 0:  # the start cell itself is blocked: take the nearest free cell's region
            free = np.argwhere(labels > 0)
            if len(free):
                k = np.argmin((free[:, 0] - i) ** 2 + (free[:, 1] - j) ** 2)
                start = labels[tuple(free[k])]
        self._grid, self._reachable = grid, (labels == start) if start else np.zeros_like(blocked)

    def _cell(self, grid, x: float, z: float) -> tuple[int, int]:
        i = int(np.clip((x - self.room[0]) // grid.cell, 0, len(grid.xs) - 1))
        j = int(np.clip((z - self.room[1]) // grid.cell, 0, len(grid.zs) - 1))
        return i, j

    def navigation(self):
        if self._reachable is None:
            self._build_navigation()
        return self._grid, self._reachable

    def room_at(self, x: float, z: float) -> str | None:
        """The id of the room whose floor holds the point (None outside every floor, or with no floors)."""
        return next((rid for rid, poly in self.floors.items() if shapely.contains_xy(shapely.Polygon(poly), x, z)),
                    None)

    def in_room(self, room_id: str | None) -> np.ndarray:
        """Per navigation cell, whether it lies in that room (every cell when the house has no floors)."""
        _, reachable = self.navigation()
        if room_id is None or room_id not in self.floors:
            return np.ones_like(reachable)
        return self._rooms == list(self.floors).index(room_id)

    def can_stand(self, x: float, z: float) -> bool:
        grid, reachable = self.navigation()
        x0, z0, x1, z1 = self.room
        if not (x0 <= x <= x1 and z0 <= z <= z1):
            return False
        return bool(reachable[self._cell(grid, x, z)])

    # ---- queries ---------------------------------------------------------------------------------
    def root(self, object_id: str) -> ObjectState:
        """The floor object that (ultimately) holds an object."""
        o = self.objects[object_id]
        seen = set()
        while o.parent is not None and o.parent in self.objects and o.parent not in seen:
            seen.add(o.id)
            o = self.objects[o.parent]
        return o

    def distance_to(self, object_id: str) -> float:
        o = self.objects[object_id]
        if object_id == self.held:
            return 0.0
        return float(o.footprint().polygon().distance(Point(self.agent_x, self.agent_z)))

    def of_type(self, type_name: str) -> list[ObjectState]:
        return [o for o in self.objects.values() if o.type == type_name and not o.sliced]

    def inside(self, receptacle_id: str) -> list[ObjectState]:
        return [o for o in self.objects.values() if o.parent == receptacle_id and not o.sliced]

    def summary(self) -> dict:
        """What changed from the house's start: the hand, the pose, and every object not in its start state."""
        flags = {}
        for o in self.objects.values():
            on = [k for k in ("is_open", "is_on", "cooled", "heated", "sliced", "picked") if getattr(o, k)]
            if on:
                flags[o.id] = on
        return {"agent": {"x": round(self.agent_x, 3), "z": round(self.agent_z, 3), "rotation": self.rotation},
                "held": self.held, "flags": flags,
                "parents": {o.id: o.parent for o in self.objects.values() if o.pickupable and not o.sliced}}


class ActionError(Exception):
    """An action that AI2-THOR would refuse, with its reason."""


def _apply_temperature(state: SymbolicState) -> None:
    for r in state.objects.values():
        if r.cold_source and (not r.openable or not r.is_open):
            for o in state.inside(r.id):
                o.cooled = True
        if r.heat_source and r.toggleable and r.is_on:
            for o in state.inside(r.id):
                o.heated = True


def execute_step(state: SymbolicState, step: PlanStep | dict) -> tuple[SymbolicState, StepResult]:
    """Run one action on a copy of the state: (new state, result). A refused action leaves the state as it was.
    `step` is a PlanStep, its JSON form (a dict whose "action" is the action dict), or a bare action dict."""
    if isinstance(step, dict) and isinstance(step.get("action"), dict):
        step = PlanStep.model_validate(step)
    index = step.index if isinstance(step, PlanStep) else 0
    action = step.action if isinstance(step, PlanStep) else step
    name = str(action.get("action", ""))
    new = state.model_copy(deep=True)
    new._grid, new._reachable, new._rooms = state._grid, state._reachable, state._rooms
    try:
        message = _execute(new, name, action)
    except ActionError as e:
        return state, StepResult(index=index, action=name, ok=False, message=str(e), state=state.summary())
    _apply_temperature(new)
    return new, StepResult(index=index, action=name, ok=True, message=message, state=new.summary())


def _target(state: SymbolicState, action: dict) -> ObjectState:
    oid = action.get("objectId")
    if not oid:
        raise ActionError(f"{action.get('action')} needs an objectId")
    o = state.objects.get(oid)
    if o is None:
        raise ActionError(f"no object {oid} in the house")
    if o.sliced:
        raise ActionError(f"{oid} has been sliced; use its slice")
    if len(state.floors) > 1 and oid != state.held:
        root = state.root(oid)
        here, there = state.room_at(state.agent_x, state.agent_z), state.room_at(root.x, root.z)
        if here != there:
            raise ActionError(f"{oid} is in {there}, the robot in {here}: go through the doors to it first")
    d = state.distance_to(oid)
    if d > INTERACT_RANGE:
        raise ActionError(f"{oid} is {d:.2f} m away, beyond reach ({INTERACT_RANGE} m): navigate to it first")
    return o


def _closed_container(state: SymbolicState, o: ObjectState) -> ObjectState | None:
    p = state.objects.get(o.parent) if o.parent else None
    return p if p is not None and p.openable and not p.is_open else None


def _execute(state: SymbolicState, name: str, action: dict) -> str:
    if name == "TeleportFull":
        pos = action.get("position") or {k: action.get(k) for k in ("x", "y", "z")}
        x, z = pos.get("x"), pos.get("z")
        if x is None or z is None:
            raise ActionError("TeleportFull needs a position")
        if not state.can_stand(float(x), float(z)):
            raise ActionError(f"TeleportFull to ({x:.2f}, {z:.2f}): not free floor reachable from the start")
        rot = action.get("rotation", {})
        state.agent_x, state.agent_z = float(x), float(z)
        state.rotation = float(rot.get("y", 0.0) if isinstance(rot, dict) else rot)
        state.horizon = float(action.get("horizon", state.horizon))
        if state.held:
            state.objects[state.held].x, state.objects[state.held].z = state.agent_x, state.agent_z
        return f"at ({x:.2f}, {z:.2f}) facing {state.rotation:.0f} degrees"
    if name not in OBJECT_ACTIONS:
        raise ActionError(f"unknown action {name!r}")
    o = _target(state, action)
    if name == "PickupObject":
        if not o.pickupable:
            raise ActionError(f"{o.id} cannot be picked up")
        if state.held:
            raise ActionError(f"the hand already holds {state.held}")
        closed = _closed_container(state, o)
        if closed is not None:
            raise ActionError(f"{o.id} is inside {closed.id}, which is closed: open it first")
        state.held, o.parent, o.picked = o.id, None, True
        return f"holding {o.id}"
    if name == "PutObject":
        if not state.held:
            raise ActionError("nothing in hand to put")
        if not o.receptacle:
            raise ActionError(f"{o.id} is not a receptacle")
        if o.openable and not o.is_open:
            raise ActionError(f"{o.id} is closed: open it first")
        held = state.objects[state.held]
        held.parent, held.x, held.y, held.z = o.id, o.x, o.y, o.z
        state.held = None
        return f"{held.id} put in/on {o.id}"
    if name in ("OpenObject", "CloseObject"):
        if not o.openable:
            raise ActionError(f"{o.id} cannot be opened or closed")
        want = name == "OpenObject"
        if o.is_open == want:
            raise ActionError(f"{o.id} is already {'open' if want else 'closed'}")
        o.is_open = want
        if want and o.toggleable and o.is_on:  # a microwave stops when its door opens
            o.is_on = False
            return f"{o.id} open (and switched off)"
        return f"{o.id} {'open' if want else 'closed'}"
    if name in ("ToggleObjectOn", "ToggleObjectOff"):
        if not o.toggleable:
            raise ActionError(f"{o.id} cannot be switched on or off")
        want = name == "ToggleObjectOn"
        if o.is_on == want:
            raise ActionError(f"{o.id} is already {'on' if want else 'off'}")
        if want and o.openable and o.is_open:
            raise ActionError(f"{o.id} must be closed to switch it on")
        o.is_on = want
        return f"{o.id} {'on' if want else 'off'}"
    # SliceObject
    if not o.sliceable:
        raise ActionError(f"{o.id} cannot be sliced")
    if state.held is None or state.objects[state.held].type not in KNIVES:
        raise ActionError(f"slicing {o.id} needs a knife in hand")
    o.sliced = True
    piece = slice_id(o.id, o.type)
    state.objects[piece] = o.model_copy(update={"id": piece, "type": _sliced_type(o.type), "sliced": False,
                                                "sliceable": False, "width": o.width / 2})
    return f"{o.id} sliced; {piece} can be picked up"


def _sliced_type(type_name: str) -> str:
    return "EggCracked" if type_name == "Egg" else f"{type_name}Sliced"

