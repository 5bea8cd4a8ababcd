"""The energy of the layout `placed + one candidate`, for every candidate pose of the next object at once.

Same terms and weights as `exact`, on axis-aligned boxes (exact for right-angle rotations) and numpy
occupancy grids. What is constant over the candidates (the placed objects among themselves) is computed
once; what the candidate changes is computed for all N candidates with broadcasting and integral images.

Navigation has two modes. `fast` (the default, a few ms for thousands of candidates) counts, with
integral images, whether a candidate covers a target's access strip or the doorway; it does not see a
candidate that cuts the free space in two elsewhere. `exact` labels the free space once per candidate
(about 0.1 ms each) and agrees with the exact energy; placers use it to re-rank their best candidates.
"""

from __future__ import annotations

import math
from collections.abc import Collection
from functools import cached_property

import numpy as np

from models.constraints.evaluate import Poses, box_gap, placement, relation, wall_clearance
from models.compiled import compiled
from models.energy import navigation as nav
from models.energy.prior import WALL_TOUCH, relation_prior
from models.energy.weights import ACCESS_DEPTH, AFF_BLOCKED, AFF_OUTSIDE, EPS, PRIOR_LAMBDA, ROBOT_RADIUS, WEIGHTS
from models.geometry import SweptBoxes, boxes, one_box, overlap_many
from models.placement.candidates import Shared, front_boxes
from models.placement.problem import PlacementProblem
from models.values import PlanObject

OVERLAP_TOL = 1e-4


class _Integral:
    """Counts of true cells of a grid mask inside axis-aligned boxes, O(1) per box."""

    def __init__(self, grid: nav.Grid, mask: np.ndarray):
        self.grid = grid
        self.table = np.zeros((mask.shape[0] + 1, mask.shape[1] + 1))
        self.table[1:, 1:] = mask.cumsum(0).cumsum(1)

    def count(self, b: np.ndarray) -> np.ndarray:
        """b: (..., 4) boxes; cells whose centres lie inside."""
        return self.count_cells(*self.cells(b))

    def cells(self, b: np.ndarray) -> tuple[np.ndarray, ...]:
        """The cell index range (i0, i1, j0, j1) of boxes b (..., 4), before empty ranges are closed. Each
        index is a non-decreasing function of one coordinate, so the range of the intersection of two boxes
        is (max i0, min i1, max j0, min j1) of theirs: exactly what `count` of the intersection computes."""
        c = self.grid.cell
        nx, nz = self.table.shape[0] - 1, self.table.shape[1] - 1

        def index(v, top):
            return np.minimum(np.maximum(v, 0), top).astype(np.intp)

        return (index(np.ceil(b[..., 0] / c - 0.5 - 1e-9), nx), index(np.floor(b[..., 2] / c - 0.5 + 1e-9) + 1, nx),
                index(np.ceil(b[..., 1] / c - 0.5 - 1e-9), nz), index(np.floor(b[..., 3] / c - 0.5 + 1e-9) + 1, nz))

    def cells_of_one(self, b) -> tuple[int, int, int, int]:
        """`cells` of one box (4,), with Python floats (the same IEEE operations, without numpy's per-call cost)."""
        c = self.grid.cell
        nx, nz = self.table.shape[0] - 1, self.table.shape[1] - 1
        x0, z0, x1, z1 = (float(v) for v in b)
        return (min(max(math.ceil(x0 / c - 0.5 - 1e-9), 0), nx), min(max(math.floor(x1 / c - 0.5 + 1e-9) + 1, 0), nx),
                min(max(math.ceil(z0 / c - 0.5 - 1e-9), 0), nz), min(max(math.floor(z1 / c - 0.5 + 1e-9) + 1, 0), nz))

    def count_cells(self, i0, i1, j0, j1) -> np.ndarray:
        i1, j1 = np.maximum(i1, i0), np.maximum(j1, j0)
        t = self.table
        return t[i1, j1] - t[i0, j1] - t[i1, j0] + t[i0, j0]


@compiled
def _sticking_out(c0, c1, d0, d1, reach, ranges, doors):
    """`CandidateEnergy._strips_reached`'s loop: for each candidate's cut (cell ranges c0:c1 x d0:d1), whether the
    bounding box of the `reach`able cells of one of the first `doors` strips (their cell ranges `ranges`) sticks
    out of it, and how many of the other strips' boxes do."""
    held = np.full((ranges.shape[0], 4), -1, np.int64)  # first row, last row, first column, last column
    for s in range(ranges.shape[0]):
        for i in range(ranges[s, 0], ranges[s, 1]):
            for j in range(ranges[s, 2], ranges[s, 3]):
                if reach[i, j]:
                    if held[s, 0] < 0:
                        held[s, 0], held[s, 1], held[s, 2], held[s, 3] = i, i, j, j
                    held[s, 1] = max(held[s, 1], i)
                    held[s, 2] = min(held[s, 2], j)
                    held[s, 3] = max(held[s, 3], j)
    door_open, reached = np.zeros(len(c0), np.bool_), np.zeros(len(c0))
    for k in range(len(c0)):
        for s in range(held.shape[0]):
            out = held[s, 0] >= 0 and not (c0[k] <= held[s, 0] and c1[k] > held[s, 1] and d0[k] <= held[s, 2]
                                           and d1[k] > held[s, 3])
            if s < doors:
                door_open[k] |= out
            elif out:
                reached[k] += 1.0
    return door_open, reached


def _intersect(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.stack([np.maximum(a[..., 0], b[..., 0]), np.maximum(a[..., 1], b[..., 1]),
                     np.minimum(a[..., 2], b[..., 2]), np.minimum(a[..., 3], b[..., 3])], axis=-1)


def _inflate(b: np.ndarray, r: float) -> np.ndarray:
    return b + np.array([-r, -r, r, r])


_PER_LAYOUT = ("reach", "reach_count")  # CandidateEnergy's lazily labelled free space


def _pose_key(p: Poses) -> tuple:
    """One pose's (x, z, rotation), as the memo of `_own` and `_pair` keys it."""
    return p.x[0], p.z[0], p.rotation[0]


class CandidateEnergy:
    """Energy terms of `placed + candidate` for N candidates of one object."""

    def __init__(self, problem: PlacementProblem, placed: list, pending: Collection[str] = ()):
        """`placed`: objects with id, x, z, rotation, width, depth (PlacedObject or Placement-like).
        `pending`: ids still to be placed after the candidate; they are not charged as missing (a per-step
        reward passes the rest of the episode's objects). Every other unplaced plan object is charged by
        E_missing and, if it is a task object, counts as unreachable in E_nav, as in `exact`."""
        self.problem = problem
        self.room = problem.plan.room
        self.types = {o.id: o.type for o in problem.plan.objects}
        self.task = {o.id for o in problem.plan.objects if o.is_task}
        self.placed = list(placed)
        self.pending = set(pending)
        self.n_objects = len(problem.plan.objects)
        self.prior = relation_prior()
        w, d = self.room.width, self.room.depth
        self.poses = {p.id: Poses.one(p.x, p.z, p.rotation, p.width, p.depth) for p in self.placed}
        self.bodies = np.array([one_box(p.x, p.z, p.width, p.depth, p.rotation) for p in self.placed]).reshape(-1, 4)
        self.clear = {p.id: problem.clearance.get(p.id, 0.0) for p in self.placed}
        self.zones = {p.id: front_boxes(p.x, p.z, p.rotation, p.width, p.depth, self.clear[p.id])
                      for p in self.placed if self.clear[p.id] > 0}
        self.room_box = np.array([0.0, 0.0, w, d])
        self._pairs: dict[tuple, float] = {}  # `_pair`, `_own` by relation and poses (shared with `after`'s copies)
        self._constant_terms()
        self.grid = nav.Grid(w, d)
        self.mesh = self.grid.mesh()
        self.start = nav.door_cells(self.grid, self.room)  # the doorway cells reachable_space starts from
        self.blocked = nav.blocked_by_boxes(self.grid, self.bodies)
        self.door_boxes = [np.array(b, float) for b in nav.door_boxes(self.room)]
        self._strips: dict[tuple, np.ndarray] = {}  # access strip by pose (shared with `after`'s copies)

    def after(self, p, pending: Collection[str] = ()) -> CandidateEnergy:
        """The set-up for the next step once `p` is placed: the constant terms are updated with `p`'s
        contributions only (its own terms, its pairs with the placed objects, one more box on the grid),
        instead of being recomputed over every placed object. Equals `CandidateEnergy(problem, placed + [p],
        pending)` up to float summation order (tested)."""
        new = self._copy()
        new.placed, new.pending = self.placed + [p], set(pending)
        pose = Poses.one(p.x, p.z, p.rotation, p.width, p.depth)
        new.poses = {**self.poses, p.id: pose}
        body = one_box(p.x, p.z, p.width, p.depth, p.rotation)[None]
        new.bodies = np.concatenate([self.bodies, body])
        clear = self.problem.clearance.get(p.id, 0.0)
        new.clear = {**self.clear, p.id: clear}
        zone = front_boxes(p.x, p.z, p.rotation, p.width, p.depth, clear) if clear > 0 else None
        new.zones = {**self.zones, p.id: zone} if zone is not None else dict(self.zones)
        new._add(self._contribution(p.id, pose, body, zone), 1)
        new.blocked = self._blocked_with(body[0])
        return new

    def without(self, oid: str, pending: Collection[str] = ()) -> CandidateEnergy:
        """The set-up with placed object `oid` taken away (to score other poses for it): its contributions
        subtracted, the grid's blocked cells recomputed. Equals `CandidateEnergy(problem, placed minus oid,
        pending)` up to float summation order (tested)."""
        new = self._copy()
        j = next(i for i, q in enumerate(self.placed) if q.id == oid)
        new.placed, new.pending = self.placed[:j] + self.placed[j + 1:], set(pending)
        new.poses = {k: v for k, v in self.poses.items() if k != oid}
        new.bodies = np.delete(self.bodies, j, axis=0)
        new.clear = {k: v for k, v in self.clear.items() if k != oid}
        new.zones = {k: v for k, v in self.zones.items() if k != oid}
        new._add(new._contribution(oid, self.poses[oid], self.bodies[j:j + 1], self.zones.get(oid)), -1)
        new.blocked = nav.blocked_without(self.grid, self.mesh, self.blocked, self.bodies[j], new.bodies)
        return new

    def _copy(self) -> CandidateEnergy:
        """A shallow copy for `after` and `without` to update, without what is labelled per layout."""
        new = object.__new__(CandidateEnergy)
        new.__dict__.update((k, v) for k, v in self.__dict__.items() if k not in _PER_LAYOUT)
        return new

    @cached_property
    def reach(self) -> np.ndarray:
        """The free cells the robot reaches from a doorway, labelled when first asked: many set-ups (the
        polish's, with an object taken away before another is placed) are never scored."""
        return self._reachable(self.blocked)

    @cached_property
    def reach_count(self) -> _Integral:
        return _Integral(self.grid, self.reach)

    def _add(self, contribution: tuple, sign: int) -> None:
        rel_sum, rel_n, collision, oob, aff = contribution
        self.rel_sum, self.rel_n = self.rel_sum + sign * rel_sum, self.rel_n + sign * rel_n
        self.collision_sum += sign * collision
        self.oob_sum += sign * oob
        self.aff_sum += sign * aff

    def _contribution(self, oid: str, pose: Poses, body: np.ndarray, zone: np.ndarray | None) -> tuple:
        """What object `oid` at `pose` (its body (1, 4), its clearance zone or None) adds to the constant
        terms of this set-up, which does not hold it: (relational sum, relation count, collision, oob,
        affordance)."""
        cons = self.problem.constraints
        oc = cons.objects[oid]
        rel_sum, rel_n = self._own(oid, oc.placement, pose), 1
        for c in oc.relations:
            if c.target in self.poses:
                rel_sum += self._pair(c.name, oid, c.target, pose, self.poses[c.target])
                rel_n += 1
        for q in self.placed:
            for c in cons.objects[q.id].relations:
                if c.target == oid:
                    rel_sum += self._pair(c.name, q.id, oid, self.poses[q.id], pose)
                    rel_n += 1
        collision = float((overlap_many(body, self.bodies)[0] ** 2).sum()) if len(self.bodies) else 0.0
        area = (body[0, 2] - body[0, 0]) * (body[0, 3] - body[0, 1])
        inside = overlap_many(body, self.room_box[None])[0, 0]
        oob = float((1 - inside / (area + EPS)) ** 2)
        aff = 0.0
        if zone is not None:  # objects standing in its clearance, its clearance outside the room
            untied = [j for j, q in enumerate(self.placed) if not cons.tied(oid, q.id)]
            aff += AFF_OUTSIDE * self._outside(zone[None])[0]
            aff += AFF_BLOCKED * int((overlap_many(zone[None], self.bodies[untied])[0] > OVERLAP_TOL).sum())
        theirs = [z for other, z in self.zones.items() if not cons.tied(other, oid)]  # clearances it stands in
        aff += AFF_BLOCKED * int((overlap_many(np.array(theirs).reshape(-1, 4), body)[:, 0] > OVERLAP_TOL).sum())
        return rel_sum, rel_n, collision, oob, aff

    def _blocked_with(self, b: np.ndarray) -> np.ndarray:
        return nav.blocked_with(self.mesh, self.blocked, b)

    def _reachable(self, blocked: np.ndarray) -> np.ndarray:
        """`navigation.reachable_space` with the doorway cells computed once per room."""
        return nav.reachable_from(blocked, self.start)

    # ---- what the placed objects contribute whatever the candidate --------------------------------

    def _constant_terms(self) -> None:
        room, ids = self.room, [p.id for p in self.placed]
        rel_sum, rel_n = 0.0, 0
        for p in self.placed:
            oc = self.problem.constraints.objects[p.id]
            pose = self.poses[p.id]
            e, _ = placement(oc.placement, pose, room.width, room.depth)
            touching = wall_clearance(pose, room.width, room.depth) <= WALL_TOUCH
            rel_sum += float(e[0] * (1 + PRIOR_LAMBDA * self.prior.wall_energy(room.type, self.types[p.id], touching)[0]))
            rel_n += 1
            for c in oc.relations:
                if c.target in self.poses:
                    rel_sum += self._pair(c.name, p.id, c.target, pose, self.poses[c.target])
                    rel_n += 1
        self.rel_sum, self.rel_n = rel_sum, rel_n
        ov = overlap_many(self.bodies, self.bodies) if len(self.bodies) else np.zeros((0, 0))
        self.collision_sum = float((np.triu(ov, 1) ** 2).sum())
        inside = overlap_many(self.bodies, self.room_box[None])[:, 0] if len(self.bodies) else np.zeros(0)
        areas = (self.bodies[:, 2] - self.bodies[:, 0]) * (self.bodies[:, 3] - self.bodies[:, 1])
        self.oob_sum = float(((1 - inside / (areas + EPS)) ** 2).sum())
        aff_sum = 0.0
        for oid, zone in self.zones.items():
            aff_sum += AFF_OUTSIDE * self._outside(zone[None])[0]
            for j, other in enumerate(ids):
                if other != oid and not self.problem.constraints.tied(oid, other):
                    aff_sum += AFF_BLOCKED * (overlap_many(zone[None], self.bodies[j:j + 1])[0, 0] > OVERLAP_TOL)
        self.aff_sum = aff_sum

    def _rel(self, name, a_id, b_id, a: Poses, b: Poses, known: tuple | None = None) -> np.ndarray:
        """`known`: (energy, gap) of the relation as soft_scores computed it for the same poses."""
        if known is not None:
            e, g = known
        else:
            g = box_gap(a, b)
            e, _ = relation(name, a, b, gap=g)
        pe = self.prior.pair_energy(self.room.type, self.types[a_id], self.types[b_id], g, a.rotation - b.rotation)
        return e * (1 + PRIOR_LAMBDA * pe)

    def _own(self, oid: str, name: str, pose: Poses) -> float:
        """The relational energy of object `oid`'s global placement `name` at one pose, memoised as `_pair`."""
        key = (name, oid, *_pose_key(pose))
        if (value := self._pairs.get(key)) is None:
            room = self.room
            e, _ = placement(name, pose, room.width, room.depth)
            touching = wall_clearance(pose, room.width, room.depth) <= WALL_TOUCH
            value = self._pairs[key] = float(
                e[0] * (1 + PRIOR_LAMBDA * self.prior.wall_energy(room.type, self.types[oid], touching)[0]))
        return value

    def _pair(self, name, a_id, b_id, a: Poses, b: Poses) -> float:
        """`_rel` of two single poses, memoised: adding and taking away objects judges the same pairs again."""
        key = (name, a_id, b_id, *_pose_key(a), *_pose_key(b))
        if (value := self._pairs.get(key)) is None:
            value = self._pairs[key] = float(self._rel(name, a_id, b_id, a, b)[0])
        return value

    def _outside(self, zones: np.ndarray) -> np.ndarray:
        area = (zones[:, 2] - zones[:, 0]) * (zones[:, 3] - zones[:, 1])
        return (area - overlap_many(zones, self.room_box[None])[:, 0]) > OVERLAP_TOL

    def terms(self) -> dict[str, float]:
        """Energy terms and weighted total of the placed objects alone (no candidate), the free space labelled
        exactly (the set-up's own grid): what `exact.layout_energy` gives for them, with `pending` not charged."""
        done = {p.id for p in self.placed} | self.pending
        missing = [o.id for o in self.problem.plan.objects if o.id not in done]
        targets = [p for p in self.placed if p.id in self.task]
        n_targets = len(targets) + sum(oid in self.task for oid in missing)
        reached = len(targets) - self._cut_off()
        terms = {"rel": math.log1p(self.rel_sum / max(self.rel_n, 1)), "collision": math.log1p(self.collision_sum),
                 "oob": math.log1p(self.oob_sum), "nav": (1 - reached / n_targets) ** 2 if n_targets else 0.0,
                 "aff": self.aff_sum / max(len(self.zones), 1), "missing": len(missing) / max(self.n_objects, 1)}
        terms["total"] = sum(WEIGHTS[k] * terms[k] for k in WEIGHTS)
        return terms

    def remember(self, shared: Shared, k: int) -> None:
        """Keep the relational energies `score` computed for candidate `k` of the step's cache `shared` as `_own`
        and `_pair` key them: `after`, placing that candidate, looks them up instead of computing them again
        (the same numbers: the same operations, element by element)."""
        pose = (shared.poses.x[k], shared.poses.z[k], shared.poses.rotation[k])
        for head, tail, values in shared.pieces:
            self._pairs[(*head, *pose, *tail)] = float(values[k])

    def _cut_off(self) -> int:
        """Placed task objects whose access strip holds no cell the robot reaches."""
        return sum(not (self.reach & nav.in_box_mask(self.grid, self._access_strip(p))).any()
                   for p in self.placed if p.id in self.task)

    def floor(self, complete: CandidateEnergy) -> float:
        """A lower bound on the energy of every layout that adds to these objects the others of `complete` (a
        set-up of the whole layout, nothing pending), wherever they go: the relational, collision, out-of-bounds
        and affordance sums only grow as objects are added, the counts they are divided by are `complete`'s, and
        a task object cut off from the robot here (or left out of `complete`) stays so, for added objects only
        shrink the free space the robot reaches. What the polish rejects a make-way move by, before the objects
        that make way are placed again."""
        left_out = [o.id for o in self.problem.plan.objects if o.id not in complete.poses]
        cut_off = self._cut_off() + sum(oid in self.task for oid in left_out)
        return (WEIGHTS["rel"] * math.log1p(self.rel_sum / max(complete.rel_n, 1))
                + WEIGHTS["collision"] * math.log1p(self.collision_sum) + WEIGHTS["oob"] * math.log1p(self.oob_sum)
                + WEIGHTS["aff"] * self.aff_sum / max(len(complete.zones), 1)
                + WEIGHTS["nav"] * (cut_off / max(len(self.task), 1)) ** 2
                + WEIGHTS["missing"] * len(left_out) / max(self.n_objects, 1))

    # ---- per candidate -----------------------------------------------------------------------------

    def score(self, obj: PlanObject, cands: np.ndarray, nav_mode: str = "fast", shared: Shared | None = None
              ) -> dict[str, np.ndarray]:
        """Energy terms and weighted total for every candidate (N, 3: x, z, rotation).

        `shared` (Episode.options): the step's cache of what the soft score and the hard filter already
        computed for these candidates (poses and boxes, wall clearance, placement and relation energies,
        squared overlaps with the placed bodies, whether the strict filter passed); the result is the same."""
        room = self.room
        x, z, rot = cands[:, 0], cands[:, 1], cands[:, 2]
        poses = shared.poses if shared is not None else Poses(x, z, rot, obj.size.x, obj.size.z)
        body = poses.boxes()
        n = len(cands)

        # relational: the candidate's own placement and relations, and placed objects' relations to it
        oc = self.problem.constraints.objects[obj.id]
        if shared is not None:
            e = shared.placement_energy(oc.placement, room.width, room.depth)
            clearance = shared.wall_clearance(room.width, room.depth)
        else:
            e, _ = placement(oc.placement, poses, room.width, room.depth)
            clearance = wall_clearance(poses, room.width, room.depth)
        touching = clearance <= WALL_TOUCH
        pieces = shared.pieces if shared is not None else []  # each (key's head, key's tail, per candidate)
        own = e * (1 + PRIOR_LAMBDA * self.prior.wall_energy(room.type, obj.type, touching))
        pieces.append(((oc.placement, obj.id), (), own))
        rel_sum, rel_n = self.rel_sum + own, self.rel_n + 1
        for i, c in enumerate(oc.relations):
            if c.target in self.poses:
                known = shared.relations.get((i, c.target)) if shared is not None else None
                target = self.poses[c.target]
                pair = self._rel(c.name, obj.id, c.target, poses, target, known)
                pieces.append(((c.name, obj.id, c.target), _pose_key(target), pair))
                rel_sum, rel_n = rel_sum + pair, rel_n + 1
        for p in self.placed:
            for c in self.problem.constraints.objects[p.id].relations:
                if c.target == obj.id:
                    pair = self._rel(c.name, p.id, obj.id, self.poses[p.id], poses)
                    pieces.append(((c.name, p.id, obj.id, *_pose_key(self.poses[p.id])), (), pair))
                    rel_sum, rel_n = rel_sum + pair, rel_n + 1
        rel = np.log1p(rel_sum / rel_n)

        # collision and out-of-bounds
        swept = None
        if shared is not None and shared.collision is not None:
            squared = shared.collision
        else:
            swept = SweptBoxes(body)
            squared = np.zeros(n)
            swept.overlapping(self.bodies, np.inf, squared)
        collision = np.log1p(self.collision_sum + squared)
        area = (body[:, 2] - body[:, 0]) * (body[:, 3] - body[:, 1])
        inside = overlap_many(body, self.room_box[None])[:, 0]
        oob = np.log1p(self.oob_sum + (1 - inside / (area + EPS)) ** 2)

        # affordance: placed objects whose clearance the candidate blocks, and the candidate's own
        aff_sum = np.full(n, self.aff_sum)
        functional = len(self.zones)
        depth = self.problem.clearance.get(obj.id, 0.0)
        if depth > 0:
            functional += 1
        if shared is None or not shared.zones_clear:  # else: every term below adds nothing (strict filter)
            swept = swept or SweptBoxes(body)
            open_zones = [zone for oid, zone in self.zones.items() if not self.problem.constraints.tied(oid, obj.id)]
            for idx, area in swept.overlaps(np.array(open_zones).reshape(-1, 4)):
                aff_sum[idx[area > OVERLAP_TOL]] += AFF_BLOCKED
            if depth > 0:
                zone = front_boxes(x, z, rot, obj.size.x, obj.size.z, depth)
                aff_sum += AFF_OUTSIDE * self._outside(zone)
                free = [b for b, p in zip(self.bodies, self.placed) if not self.problem.constraints.tied(obj.id, p.id)]
                for idx, area in SweptBoxes(zone).overlaps(np.array(free).reshape(-1, 4)):
                    aff_sum[idx[area > OVERLAP_TOL]] += AFF_BLOCKED
        aff = aff_sum / max(functional, 1)

        nav_e = self._navigation(obj, cands, body) if nav_mode == "fast" else self._navigation_exact(obj, cands, body)
        missing = np.full(n, len(self._missing(obj)) / max(self.n_objects, 1))
        terms = {"rel": rel, "collision": collision, "oob": oob, "nav": nav_e, "aff": aff, "missing": missing}
        terms["total"] = sum(WEIGHTS[k] * terms[k] for k in WEIGHTS)
        return terms

    def _reachable_strip(self, strip: np.ndarray, cut: np.ndarray | tuple) -> np.ndarray:
        """Does `strip` (4,) or (N, 4) hold a reachable cell outside the candidate's inflated body `cut` (N, 4)?
        `cut` may be given as its cell ranges (`_Integral.cells`), computed once for all strips."""
        rc = self.reach_count
        if not isinstance(cut, tuple):
            return (rc.count(strip) - rc.count(_intersect(np.broadcast_to(strip, cut.shape), cut))) > 0
        s0, s1, t0, t1 = rc.cells(np.asarray(strip))
        c0, c1, d0, d1 = cut
        inter = rc.count_cells(np.maximum(s0, c0), np.minimum(s1, c1), np.maximum(t0, d0), np.minimum(t1, d1))
        return (rc.count_cells(s0, s1, t0, t1) - inter) > 0

    def _strips_reached(self, strips: list, doors: int, cut: tuple) -> tuple[np.ndarray, np.ndarray]:
        """`_reachable_strip` for strips (4,) the same for every candidate, the first `doors` of them doorways:
        (whether one of those holds a reachable cell outside each candidate's cut, how many of the others do). The
        count of a strip's reachable cells minus those in the cut is positive exactly when the cut's cell range
        does not cover the bounding box of those cells (a box sticking out of the cut has a reachable cell on its
        outermost row or column outside it), so only that box is needed per strip."""
        ranges = np.array([self.reach_count.cells_of_one(strip) for strip in strips], np.int64).reshape(-1, 4)
        return _sticking_out(*(np.ascontiguousarray(c, np.int64) for c in cut), self.reach, ranges, doors)

    def _access_strip(self, p) -> np.ndarray:
        """The access strip (4,) in front of placed object `p`, made once per pose (shared with `after`'s copies)."""
        key = (p.x, p.z, p.rotation, p.width, p.depth)
        if key not in self._strips:
            self._strips[key] = front_boxes(p.x, p.z, p.rotation, p.width, p.depth, ACCESS_DEPTH)
        return self._strips[key]

    def _missing(self, obj: PlanObject) -> list[str]:
        """Plan objects neither placed, nor the candidate, nor pending."""
        done = {p.id for p in self.placed} | {obj.id} | self.pending
        return [o.id for o in self.problem.plan.objects if o.id not in done]

    def _targets(self, obj: PlanObject) -> tuple[list, bool, int]:
        """Placed task objects, whether the candidate is one, and how many there are in all (missing task
        objects count: they are never reached)."""
        targets = [p for p in self.placed if p.id in self.task]
        is_target = obj.id in self.task
        missing = sum(oid in self.task for oid in self._missing(obj))
        return targets, is_target, len(targets) + is_target + missing

    def _navigation(self, obj: PlanObject, cands: np.ndarray, body: np.ndarray) -> np.ndarray:
        targets, is_target, n_targets = self._targets(obj)
        if n_targets == 0:
            return np.zeros(len(cands))
        cut = self.reach_count.cells(_inflate(body, ROBOT_RADIUS))
        strips = [*self.door_boxes, *(self._access_strip(p) for p in targets)]
        door_open, reached = self._strips_reached(strips, len(self.door_boxes), cut)
        if is_target:
            x, z, rot = cands[:, 0], cands[:, 1], cands[:, 2]
            strip = front_boxes(x, z, rot, obj.size.x, obj.size.z, ACCESS_DEPTH)
            reached += self._reachable_strip(strip, cut)
        rho = np.where(door_open, reached / n_targets, 0.0)
        return (1 - rho) ** 2

    def exact_navigation(self, obj: PlanObject, cands: np.ndarray) -> np.ndarray:
        """The navigation term of `score(..., nav_mode="exact")` alone, for candidates (N, 3)."""
        return self._navigation_exact(obj, cands, boxes(cands[:, 0], cands[:, 1], obj.size.x, obj.size.z, cands[:, 2]))

    def _navigation_exact(self, obj: PlanObject, cands: np.ndarray, body: np.ndarray) -> np.ndarray:
        """Label the free space with each candidate in place: what the exact energy computes, per candidate."""
        targets, is_target, n_targets = self._targets(obj)
        if n_targets == 0:
            return np.zeros(len(cands))
        strips = [nav.in_box_mask(self.grid, self._access_strip(p)) for p in targets]
        out = np.empty(len(cands))
        for i, (x, z, rot) in enumerate(cands):
            reach = self._reachable(self._blocked_with(body[i]))
            reached = sum(bool((reach & s).any()) for s in strips)
            if is_target:
                own = front_boxes(x, z, rot, obj.size.x, obj.size.z, ACCESS_DEPTH)
                reached += bool((reach & nav.in_box_mask(self.grid, own)).any())
            out[i] = (1 - reached / n_targets) ** 2
        return out
