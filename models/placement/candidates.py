"""Candidate poses for one object and their scores, computed for all candidates at once (numpy).

Shared by the placers: a grid of centres (0.1 m in rooms up to 30 m^2) including every wall-flush
position, in four rotations; hard filters (inside the room, no overlap, door clearance, front
clearance both ways); and a soft score from the object's constraints to already placed objects.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from models.constraints.evaluate import Poses, box_gap, placement, relation, relation_met, wall_clearance
from models.geometry import SweptBoxes, boxes, half_extents, one_box, overlap_many, turn
from models.placement.problem import DOOR_CLEARANCE, PlacementProblem
from models.values import PlanObject

ROTATIONS = (0.0, 90.0, 180.0, 270.0)
OVERLAP_TOL = 1e-4  # m^2: touching is allowed, overlapping is not
GLOBAL_WEIGHT = 2.0
ENERGY_WEIGHT = 0.5


@dataclass(frozen=True)
class PlacedObject:
    id: str
    x: float
    z: float
    rotation: float
    width: float
    depth: float
    body: np.ndarray  # (4,) box
    front: np.ndarray | None  # (4,) clearance box in front, or None


def poses_of(cands: np.ndarray, obj: PlanObject, body: np.ndarray | None = None) -> Poses:
    """The poses `cands` (N, 3) of `obj`; `body`: their boxes if known (`CandidateScorer.bodies`), the same numbers
    `Poses.boxes` would compute (geometry.boxes on these poses), kept instead of computed again."""
    poses = Poses(cands[:, 0], cands[:, 1], cands[:, 2], obj.size.x, obj.size.z)
    if body is not None:
        poses.__dict__["_boxes"] = body
    return poses


@dataclass
class Shared:
    """What the soft score and the vectorised energy both compute for the same candidates of one object,
    computed once per step (Episode.options) and handed to both: the poses (their boxes cached), wall
    clearance, the placement energy, each relation's energy and gap, and what the hard filter already knows."""

    poses: Poses
    clearance: np.ndarray | None = None  # constraints.evaluate.wall_clearance
    placement: np.ndarray | None = None  # energy of the object's global placement constraint
    relations: dict = field(default_factory=dict)  # (relation index, target) -> (energy, box gap)
    collision: np.ndarray | None = None  # squared overlap areas with the placed bodies, summed in placed order
    zones_clear: bool = False  # the strict hard filter passed: no open front zone is blocked, own zone free
    pieces: list = field(default_factory=list)  # the relational energies per candidate (CandidateEnergy.score)

    @classmethod
    def of(cls, cands: np.ndarray, obj: PlanObject, body: np.ndarray | None = None) -> Shared:
        return cls(poses_of(cands, obj, body))

    def wall_clearance(self, width: float, depth: float) -> np.ndarray:
        if self.clearance is None:
            self.clearance = wall_clearance(self.poses, width, depth)
        return self.clearance

    def placement_energy(self, name: str, width: float, depth: float) -> np.ndarray:
        if self.placement is None:
            self.placement = placement(name, self.poses, width, depth, clearance=self.wall_clearance(width, depth))[0]
        return self.placement


def grid_boxes(cands: np.ndarray, width: float, depth: float, blocks=None) -> np.ndarray:
    """`geometry.boxes` of every candidate, with the rotation's half extents computed once per rotation
    instead of once per candidate (the same numbers, tested); `blocks`: `CandidateScorer.grid`'s."""
    if blocks is None:
        blocks = [(m, None, r) for r in np.unique(cands[:, 2]) for m in [cands[:, 2] == r]]
    ex, ez = np.empty(len(cands)), np.empty(len(cands))
    for a, b, r, *_ in blocks:
        hx, hz = half_extents(np.asarray(width, float), np.asarray(depth, float), np.array([r]))
        sel = a if b is None else slice(a, b)
        ex[sel], ez[sel] = hx[0], hz[0]
    x, z = cands[:, 0], cands[:, 1]
    return np.stack([x - ex, z - ez, x + ex, z + ez], axis=-1)


def front_boxes(x, z, rotation, width, depth, clearance: float) -> np.ndarray:
    """The box of the `clearance`-deep strip in front of each pose ((4,) for one pose given as numbers)."""
    off = depth / 2 + clearance / 2
    if np.ndim(x) == 0 and np.ndim(rotation) == 0:  # one pose: the same values without numpy's per-call cost
        s, c = turn(float(rotation))
        return one_box(x + s * off, z + c * off, width, clearance, rotation)
    r = np.radians(rotation)
    return boxes(x + np.sin(r) * off, z + np.cos(r) * off, width, clearance, rotation)


class CandidateScorer:
    def __init__(self, problem: PlacementProblem, step: float | None = None, like: CandidateScorer | None = None):
        """`like`: a scorer of the same plan (in another order, `PlacementProblem.with_first`) whose caches this one
        shares: they hold what depends on the room and the objects only (candidates, their boxes, strips, and
        whether they meet their global placement), and a second solve of the plan would make them again."""
        self.problem = problem
        if like is not None:
            assert like.problem.plan is problem.plan, "a scorer shares its caches only with one of the same plan"
            self.__dict__.update({k: v for k, v in like.__dict__.items() if k != "problem"})
            return
        room = problem.plan.room
        self.width, self.depth = room.width, room.depth
        self.step = step or (0.1 if room.width * room.depth <= 30 else 0.15)
        self.door_zones = np.array([self._door_zone(d.wall, d.center, d.width) for d in room.doors]).reshape(-1, 4)
        self._grids: dict[tuple[float, float], np.ndarray] = {}
        self._bodies: dict[tuple[float, float], tuple[np.ndarray, np.ndarray]] = {}
        self._swept: dict[tuple[float, float], SweptBoxes] = {}
        self._strips: dict[str, tuple[np.ndarray, SweptBoxes]] = {}
        self._placement_met: dict[str, np.ndarray] = {}
        self._relation_met: dict[tuple, np.ndarray] = {}

    def _door_zone(self, wall: str, center: float, width: float) -> list[float]:
        half, c = width / 2 + 0.05, DOOR_CLEARANCE
        return {"south": [center - half, 0, center + half, c],
                "north": [center - half, self.depth - c, center + half, self.depth],
                "west": [0, center - half, c, center + half],
                "east": [self.width - c, center - half, self.width, center + half]}[wall]

    def _axis(self, half: float, length: float) -> np.ndarray:
        if 2 * half > length + 1e-9:
            return np.empty(0)
        v = np.round(np.concatenate([np.arange(half, length - half, self.step), [length - half]]), 4)
        d = np.diff(v)
        if (d[:-1] > 0).all() and d[-1:].size and d[-1] >= 0:  # sorted already, at most the end repeated
            return v if d[-1] > 0 else v[:-1]  # what np.unique returns, without its sort
        return np.unique(v)

    def candidates(self, obj: PlanObject) -> np.ndarray:
        """(N, 3) array of x, z, rotation for every pose that keeps the footprint inside the room."""
        return self.grid(obj)[0]

    def grid(self, obj: PlanObject) -> tuple[np.ndarray, tuple[tuple, ...]]:
        """`candidates` and their blocks (start, stop, rotation, xs, zs): per rotation, x-major over the axes'
        centres xs, zs."""
        key = (obj.size.x, obj.size.z)
        if key not in self._grids:
            axes, blocks, start = {}, [], 0
            for rot in ROTATIONS:
                hx, hz = (obj.size.x / 2, obj.size.z / 2) if rot in (0.0, 180.0) else (obj.size.z / 2, obj.size.x / 2)
                if (hx, hz) not in axes:
                    axes[(hx, hz)] = self._axis(hx, self.width), self._axis(hz, self.depth)
                xs, zs = axes[(hx, hz)]
                if len(xs) and len(zs):
                    blocks.append((start, start + len(xs) * len(zs), rot, xs, zs))
                    start += len(xs) * len(zs)
            cands = np.empty((start, 3))
            for a, b, rot, xs, zs in blocks:  # = np.meshgrid(xs, zs, indexing="ij"), raveled
                cands[a:b, 0], cands[a:b, 1], cands[a:b, 2] = np.repeat(xs, len(zs)), np.tile(zs, len(xs)), rot
            cands.setflags(write=False)  # shared by every step and repair that places an object of this size
            self._grids[key] = cands, tuple(blocks)
        return self._grids[key]

    def bodies(self, obj: PlanObject) -> tuple[np.ndarray, np.ndarray]:
        """(`grid`'s candidates, their bodies' boxes), made once per object size (read-only)."""
        key = (obj.size.x, obj.size.z)
        if key not in self._bodies:
            cands, blocks = self.grid(obj)
            body = grid_boxes(cands, obj.size.x, obj.size.z, blocks)
            body.setflags(write=False)
            self._bodies[key] = cands, body
        return self._bodies[key]

    def swept(self, obj: PlanObject) -> SweptBoxes:
        """The sweep structure of `bodies`' boxes, made once per object size (every step and repair that looks
        at all the poses of an object shares it)."""
        key = (obj.size.x, obj.size.z)
        if key not in self._swept:
            self._swept[key] = SweptBoxes(self.bodies(obj)[1])
        return self._swept[key]

    def strips(self, obj: PlanObject, cands: np.ndarray, swept: SweptBoxes) -> tuple[np.ndarray, SweptBoxes]:
        """(whether each pose's front clearance strip lies inside the room, the strips' sweep structure) for the
        poses `cands` of `obj` (which has a clearance); made once per object when they are all its poses (`swept`
        is `self.swept(obj)`), as every step and repair that looks at all of them asks again."""
        every = swept is self._swept.get((obj.size.x, obj.size.z))
        if every and obj.id in self._strips:
            return self._strips[obj.id]
        front = front_boxes(cands[:, 0], cands[:, 1], cands[:, 2], obj.size.x, obj.size.z,
                            self.problem.clearance[obj.id])
        inside = (front[:, 0] >= -1e-6) & (front[:, 1] >= -1e-6) & \
            (front[:, 2] <= self.width + 1e-6) & (front[:, 3] <= self.depth + 1e-6)
        made = inside, SweptBoxes(front)
        if every:
            self._strips[obj.id] = made
        return made

    def placement_met(self, obj: PlanObject, name: str) -> np.ndarray:
        """Whether each pose of `bodies` meets the global placement `name` (`edge`, `middle`) of `obj`: it does
        not depend on the other objects, so it is computed once per object."""
        if obj.id not in self._placement_met:
            cands, body = self.bodies(obj)
            self._placement_met[obj.id] = placement(name, poses_of(cands, obj, body), self.width, self.depth)[1]
        return self._placement_met[obj.id]

    def relation_met(self, obj: PlanObject, name: str, other: tuple[float, float, float, float, float],
                     reverse: bool = False) -> np.ndarray:
        """Whether each pose of `bodies` meets `obj name other` (`reverse`: `other name obj`), `other` one pose
        (x, z, rotation, width, depth). Kept per object, relation and pose of the other: the polish counts the
        constraints met again and again with the same objects where they stand."""
        key = (obj.id, name, reverse, other)
        if key not in self._relation_met:
            cands, body = self.bodies(obj)
            mine, theirs = poses_of(cands, obj, body), Poses.one(*other)
            self._relation_met[key] = relation_met(name, theirs, mine) if reverse else relation_met(name, mine, theirs)
        return self._relation_met[key]

    def place(self, obj: PlanObject, x: float, z: float, rotation: float) -> PlacedObject:
        clearance = self.problem.clearance.get(obj.id, 0.0)
        body = one_box(x, z, obj.size.x, obj.size.z, rotation)
        front = front_boxes(x, z, rotation, obj.size.x, obj.size.z, clearance) if clearance > 0 else None
        return PlacedObject(obj.id, x, z, rotation, obj.size.x, obj.size.z, body, front)

    def evaluate(self, obj: PlanObject, placed: list[PlacedObject], strict: bool = True
                 ) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
        """(candidates, scores, energy terms) with -inf scores for poses that fail a hard filter."""
        cands = self.candidates(obj)
        if len(cands) == 0:
            return cands, np.empty(0), {}
        x, z, rot = cands[:, 0], cands[:, 1], cands[:, 2]
        body = boxes(x, z, obj.size.x, obj.size.z, rot)
        ok = np.ones(len(cands), bool)
        if placed:
            ok &= overlap_many(body, np.stack([p.body for p in placed])).max(axis=1) <= OVERLAP_TOL
        if len(self.door_zones):
            ok &= overlap_many(body, self.door_zones).max(axis=1) <= OVERLAP_TOL
        if strict:
            clearance = self.problem.clearance.get(obj.id, 0.0)
            free = [p for p in placed if not self.problem.constraints.tied(obj.id, p.id)]
            if clearance > 0:
                front = front_boxes(x, z, rot, obj.size.x, obj.size.z, clearance)
                inside = (front[:, 0] >= -1e-6) & (front[:, 1] >= -1e-6) & \
                         (front[:, 2] <= self.width + 1e-6) & (front[:, 3] <= self.depth + 1e-6)
                ok &= inside
                if free:
                    ok &= overlap_many(front, np.stack([p.body for p in free])).max(axis=1) <= OVERLAP_TOL
            fronts = [p.front for p in free if p.front is not None]
            if fronts:
                ok &= overlap_many(body, np.stack(fronts)).max(axis=1) <= OVERLAP_TOL
        scores, terms = self.soft_scores(obj, cands, placed)
        return cands, np.where(ok, scores, -np.inf), terms

    def soft_scores(self, obj: PlanObject, cands: np.ndarray, placed: list[PlacedObject], shared: Shared | None = None
                    ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """`shared`: the step's cache (see Shared); what is computed here is kept there for the energy."""
        poses = shared.poses if shared is not None else Poses(cands[:, 0], cands[:, 1], cands[:, 2], obj.size.x,
                                                              obj.size.z)
        oc = self.problem.constraints.objects[obj.id]
        if shared is not None:
            c = shared.wall_clearance(self.width, self.depth)
            g_energy, g_ok = placement(oc.placement, poses, self.width, self.depth, clearance=c)
            shared.placement = g_energy
        else:
            g_energy, g_ok = placement(oc.placement, poses, self.width, self.depth)
        score = GLOBAL_WEIGHT * g_ok - ENERGY_WEIGHT * g_energy
        rel_energy = np.zeros(len(cands))
        by_id = {p.id: p for p in placed}
        for i, c in enumerate(oc.relations):
            target = by_id.get(c.target)
            if target is None:
                continue
            other = Poses.one(target.x, target.z, target.rotation, target.width, target.depth)
            if shared is not None:  # the gap `relation` would compute itself, kept for the energy's prior
                gap = box_gap(poses, other)
                e, sat = relation(c.name, poses, other, gap=gap)
                shared.relations[(i, c.target)] = (e, gap)
            else:
                e, sat = relation(c.name, poses, other)
            score = score + sat - ENERGY_WEIGHT * e
            rel_energy = rel_energy + e
        return score, {"global": g_energy, "relations": rel_energy}
