"""Apartments: several rooms that share walls, joined by doors (issue 12).

Every room keeps its own local frame (x in [0, width], z in [0, depth], the walls of models.values.room);
`x`, `z` place that frame's origin in the house. A door between two rooms is an Opening in both rooms'
`Room.doors`, so each room's placer keeps it clear; `Doorway` names the rooms it joins.
"""

from __future__ import annotations

from pydantic import Field

from models.values.common import Provenance, Value
from models.values.constraint_plan import ConstraintPlan
from models.values.layout import Layout, Unplaced
from models.values.room import Room
from models.values.room_plan import RoomPlan
from models.values.scene import AgentPose, Scene
from models.values.task_graph import TaskGraph

OUTSIDE = "outside"
APARTMENT = "apartment"  # the room type an apartment is asked for, and stored under


class HouseRoom(Value):
    id: str  # "room|<n>", as the house JSON names it
    room: Room
    x: float  # the house position of the room's (0, 0) corner
    z: float

    @property
    def number(self) -> int:
        """The room's number in the house JSON's ids (`Fridge|<n>|0`)."""
        return int(self.id.split("|")[-1])

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """(xmin, zmin, xmax, zmax) in the house."""
        return self.x, self.z, self.x + self.room.width, self.z + self.room.depth


class Doorway(Value):
    """A door in the house frame: `rooms` are the two rooms it joins (OUTSIDE for the entrance)."""

    id: str
    rooms: tuple[str, str]
    x0: float  # the wall piece the door is cut into, from its lower-coordinate end
    z0: float
    x1: float
    z1: float
    center: float  # along that piece, from (x0, z0)
    width: float = Field(gt=0)
    asset_id: str

    @property
    def middle(self) -> tuple[float, float]:
        """The door's middle (x, z) in the house frame."""
        return (self.x0 + self.center, self.z0) if self.z0 == self.z1 else (self.x0, self.z0 + self.center)


class Floorplan(Value):
    rooms: list[HouseRoom]
    doors: list[Doorway]
    entrance: str  # the id of the door from outside
    provenance: Provenance | None = None

    def room(self, room_id: str) -> HouseRoom:
        return next(r for r in self.rooms if r.id == room_id)

    @property
    def size(self) -> tuple[float, float]:
        return (max(r.bounds[2] for r in self.rooms), max(r.bounds[3] for r in self.rooms))


class HousePlan(Value):
    """The floorplan and one RoomPlan per room (same order), each in its room's local frame."""

    id: str
    floorplan: Floorplan
    room_plans: list[RoomPlan]
    assignment: dict[str, str] = Field(default_factory=dict)  # task object type -> the room id it went to
    warnings: list[str] = Field(default_factory=list)


class RobotPath(Value):
    """The robot's way from its start through the doors to each task object, in the house frame."""

    points: list[tuple[float, float]] = Field(default_factory=list)
    visits: list[str] = Field(default_factory=list)  # the object ids reached, in order
    unreachable: list[str] = Field(default_factory=list)


class Apartment(Value):
    """The placed apartment: one Scene per room (local frame, floorplan order) plus what spans rooms."""

    id: str
    task_graph: TaskGraph
    plan: HousePlan
    plans: list[ConstraintPlan]  # per room, floorplan order, as placed
    layouts: list[Layout]
    scenes: list[Scene]
    robot_start: AgentPose  # house frame, just inside the entrance
    vr_anchor: AgentPose | None = None  # house frame, in the anchor's room
    anchor_room: str | None = None
    key_nav: float | None = None  # share of the task objects the robot reaches through the doors
    e_nav: float = 0.0  # (1 - key_nav)^2, every unplaced task object unreachable
    path: RobotPath = Field(default_factory=RobotPath)
    unplaced: list[Unplaced] = Field(default_factory=list)
    warnings: list[str] = Field(default_factory=list)

    @property
    def floorplan(self) -> Floorplan:
        return self.plan.floorplan
