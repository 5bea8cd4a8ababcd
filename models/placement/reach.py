"""Which task objects the robot can reach from the doorway (Key_NAV's test: a free cell of the object's access
strip connected to a doorway cell), on the navigation grid of one room: what the repairs restore and what a
placer's reach guard keeps (`Episode.guarded`, `Episode.first_kept`).

In a room the robot crosses (`Room.crossed`: a room with several doors, an apartment's or a single room's) its other
doors are wanted too: the robot starts in the first doorway, and each other door it cannot reach counts as a task
object out of reach, under a gate's id (`GATE`), so that the same guard and repairs keep the way through the room
open."""

from __future__ import annotations

from collections.abc import Iterable, Iterator

import numpy as np

from models.energy import navigation as nav
from models.energy.weights import ACCESS_DEPTH
from models.placement.candidates import PlacedObject, front_boxes
from models.placement.problem import PlacementProblem


GATE = "door|{}"  # the id under which a crossed room's door the robot cannot reach is counted out of reach


class Reach:
    """Which task objects (and, in a crossed room, doors) the robot can reach, on the navigation grid of one room."""

    def __init__(self, problem: PlacementProblem):
        room = problem.plan.room
        self.grid = nav.Grid(room.width, room.depth)
        self.mesh = self.grid.mesh()
        self.task = {o.id for o in problem.plan.objects if o.is_task}
        self._strips: dict[tuple, np.ndarray] = {}
        doors = nav.door_masks(self.grid, room)
        if room.crossed and len(doors) > 1:
            self.start = doors[0]
            self.gates = {GATE.format(i): door for i, door in enumerate(doors[1:], 1)}
            self.gate_centres = {GATE.format(i): _centre(box) for i, box in enumerate(nav.door_boxes(room)[1:], 1)}
        else:
            self.start = nav.door_cells(self.grid, room)
            self.gates, self.gate_centres = {}, {}

    def strip(self, p: PlacedObject) -> np.ndarray:
        key = (p.x, p.z, p.rotation, p.width, p.depth)
        if key not in self._strips:
            self._strips[key] = nav.in_box_mask(self.grid, front_boxes(p.x, p.z, p.rotation, p.width, p.depth,
                                                                      ACCESS_DEPTH))
        return self._strips[key]

    def blocked(self, placed: list[PlacedObject]) -> np.ndarray:
        return nav.blocked_by_boxes(self.grid, np.array([p.body for p in placed]).reshape(-1, 4))

    def unreachable(self, placed: list[PlacedObject], blocked: np.ndarray | None = None,
                    reachable: np.ndarray | None = None) -> list[str]:
        """The task objects of `placed` out of reach, then a crossed room's doors out of reach (`blocked`,
        `reachable`: its grids, if known; an energy set-up's `reachable` starts from every door, so a crossed room
        floods its own from the first)."""
        if reachable is None or self.gates:
            reachable = nav.reachable_from(self.blocked(placed) if blocked is None else blocked, self.start)
        out = [p.id for p in placed if p.id in self.task and not (self.strip(p) & reachable).any()]
        return out + [gate for gate, door in self.gates.items() if not (door & reachable).any()]

    def out_with(self, others: list[PlacedObject], base: np.ndarray, pose: PlacedObject) -> int:
        """How many task objects are out of reach once `pose` joins `others`, whose blocked grid is `base`
        (updated around `pose` only)."""
        return len(self.unreachable([*others, pose], nav.blocked_with(self.mesh, base, pose.body)))

    def keeping(self, placed: list[PlacedObject], poses: Iterable[PlacedObject], blocked: np.ndarray,
                reachable: np.ndarray) -> Iterator[bool]:
        """For each of `poses` (one object's), lazily: does it leave no more task objects out of reach than
        `placed` leaves now (the pose's own object counted if it is a task object)? `blocked`, `reachable`: the
        grids of `placed` (an energy set-up's)."""
        now = len(self.unreachable(placed, blocked, reachable))
        return (self.out_with(placed, blocked, pose) <= now for pose in poses)


def _centre(box: tuple[float, float, float, float]) -> tuple[float, float]:
    return (box[0] + box[2]) / 2, (box[1] + box[3]) / 2
