"""Companions' pass after the constraints' polish (not in the paper): a plan states the relations its author
thought of, not every habit of a furnished room. In the hand-built iTHOR rooms a chair stands at its table
and a sink at its counter whether or not anyone said so. `companions` reads those habits from the energy's
relation prior (the 92 training rooms, never the 28 the realism judge is fitted on): A keeps a B near when
most A's in rooms with a B have their nearest B within a small gap (`RelationPrior.companion_gap`).

Once the polish is done, each movable object with a companion too far (once each, in placing order) is
moved to the legal pose that keeps the most companions near, then of lowest energy, if that keeps more
habits in the whole layout and costs nothing the other passes guard: its constraints met do not fall, the
layout's energy does not rise and no more task objects are out of the robot's reach. Fixed objects never
move; each move is a placement step; the time counts in PTO. A `crowded` room is left alone: on 16 `dense`
plans off the benchmark's sample no move was found there.
"""

from __future__ import annotations

import numpy as np

from models.constraints.evaluate import gap_of_boxes
from models.energy.prior import relation_prior
from models.geometry import SweptBoxes, one_box
from models.placement.base import StepObserver
from models.placement.candidates import PlacedObject
from models.placement.greedy import Episode
from models.placement.moves import legal_poses
from models.placement.polish import Move, Standing, crowded, free_move, met, met_among
from models.values import ConstraintPlan

Companions = dict[str, list[tuple[str, float]]]  # type -> [(companion type, largest habitual gap)]


def companions(plan: ConstraintPlan) -> Companions:
    """For each type of the plan, the other types of the plan it keeps near by habit, with the gap."""
    prior, types = relation_prior(), sorted({o.type for o in plan.objects})
    out: Companions = {}
    for a in types:
        near = [(b, gap) for b in types if b != a
                and (gap := prior.companion_gap(plan.room.type, a, b)) is not None]
        if near:
            out[a] = near
    return out


def _footprint(p: PlacedObject) -> np.ndarray:
    return one_box(p.x, p.z, p.width, p.depth, p.rotation)


class Habits:
    """The plan's companions and the footprints of a layout's objects (id -> box), to count habits kept."""

    def __init__(self, plan: ConstraintPlan, placed: list[PlacedObject]):
        self.comp = companions(plan)
        self.types = {o.id: o.type for o in plan.objects}
        self.feet = {p.id: _footprint(p) for p in placed}

    def _each(self, oid: str, feet: np.ndarray, layout: dict[str, np.ndarray]):
        """(companion type, for each footprint of `feet` (N, 4) whether one of that type among the other
        objects of `layout` is within the habitual gap), for each companion of `oid`."""
        for b, gap in self.comp.get(self.types[oid], ()):
            theirs = [box for q, box in layout.items() if self.types[q] == b and q != oid]
            if not theirs:
                yield b, np.zeros(len(feet), bool)
            else:
                yield b, gap_of_boxes(feet[:, None], np.stack(theirs)[None]).min(axis=1) <= gap + 1e-9

    def near(self, oid: str, feet: np.ndarray, layout: dict[str, np.ndarray] | None = None) -> np.ndarray:
        """For each footprint of `feet` (N, 4) that `oid` could take: how many of its companions have one of
        theirs within the habitual gap among the other objects of `layout` (default: this one)."""
        count = np.zeros(len(feet), int)
        for _, ok in self._each(oid, feet, self.feet if layout is None else layout):
            count += ok
        return count

    def beside(self, oid: str, box: np.ndarray) -> list[str]:
        """The companion types of `oid` that have one of theirs near the footprint `box` (4,)."""
        return [b for b, ok in self._each(oid, box[None], self.feet) if ok[0]]

    def kept(self, layout: dict[str, np.ndarray] | None = None) -> int:
        """Habits kept in `layout` (default: this one): (object, companion type) pairs with one near enough."""
        layout = self.feet if layout is None else layout
        return sum(int(self.near(q, box[None], layout)[0]) for q, box in layout.items() if self.types[q] in self.comp)

    def kept_with(self, oid: str, box: np.ndarray, now: int) -> int:
        """`kept` of this layout with `oid` at `box`, given `now`, this layout's: only the pairs of `oid` and of
        the objects that keep its type near are counted again."""
        layout, t = {**self.feet, oid: box}, self.types[oid]
        again = [q for q in self.feet if q == oid or any(b == t for b, _ in self.comp.get(self.types[q], ()))]
        return now + sum(int(self.near(q, layout[q][None], layout)[0]) - int(self.near(q, self.feet[q][None])[0])
                         for q in again if self.types[q] in self.comp)


def _move(ep: Episode, now: Standing, habits: Habits, p: PlacedObject, before: int) -> Move | None:
    """The best move of `p` in the layout `ep.placed`, which keeps `before` habits (see the module), or None."""
    wanted, current = habits.comp[habits.types[p.id]], int(habits.near(p.id, habits.feet[p.id][None])[0])
    if current == len(wanted):
        return None
    others = [q for q in ep.placed if q is not p]
    obj = ep.problem.plan.object(p.id)
    cands, body = ep.scorer.bodies(obj)
    gain = habits.near(p.id, body)
    better = np.flatnonzero(gain > current)
    if not len(better):
        return None
    cands, body, gain = cands[better], body[better], gain[better]
    legal = legal_poses(ep, obj, others, cands, SweptBoxes(body), relax=False)
    legal = legal[met(ep, p.id, better[legal], others) >= met_among(ep, ep.placed, {p.id})]
    if not len(legal):
        return None
    return free_move(ep, now, obj, others, cands, legal, gain, now.setup.without(p.id),
                     why=lambda pose: f"standing by its {', '.join(habits.beside(p.id, _footprint(pose)))}, as in the "
                                      "iTHOR rooms",
                     accept=lambda pose: habits.kept_with(p.id, _footprint(pose), before) > before)


def keep_companions(ep: Episode, observer: StepObserver | None = None) -> list[str]:
    """Move the movable objects of the finished episode `ep` whose companions are too far, each once, when
    that keeps more habits at no cost (none in a `crowded` room; see the module); the ids moved, in order."""
    if crowded(ep.problem.plan):
        return []
    habits, moved, now = Habits(ep.problem.plan, ep.placed), [], Standing(ep)
    before = habits.kept()
    for oid in [p.id for p in ep.placed if habits.types[p.id] in habits.comp and p.id not in ep.problem.fixed]:
        move = _move(ep, now, habits, next(q for q in ep.placed if q.id == oid), before)
        if move is None:
            continue
        now.moved(move)
        habits.feet[oid] = _footprint(move.placed[-1])
        before = habits.kept()
        moved.append(oid)
        if observer is not None:
            observer(move.steps[0])
    return moved
