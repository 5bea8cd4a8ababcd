"""The greedy placer: for each object in the solvers' order, the candidate pose of lowest immediate energy.

It is the simplest thing that could replace Plan2Place (issue 8): the same candidates, hard filters and
per-step energy (models.energy.vectorised with the episode's remaining objects pending), no look-ahead, and
the same repairs at the end (models.placement.repair).
`Episode` is the step machinery both share.
"""

from __future__ import annotations

import copy
import time
from collections.abc import Callable, Collection
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from models.energy.vectorised import CandidateEnergy
from models.energy.weights import WEIGHTS
from models.placement.base import Fixed, PlacementStep, StepObserver
from models.placement import blas
from models.geometry import SweptBoxes
from models.placement.candidates import OVERLAP_TOL, CandidateScorer, PlacedObject, Shared
from models.placement.problem import PlacementProblem
from models.placement.reach import Reach
from models.placement.result import NO_ROOM, make_layout
from models.placement.ties import steady
from models.values import ConstraintPlan, Layout, PlanObject

GUARD_TRIES = 48  # Episode.guarded: candidates tried, most wanted first (Plan2Place's subset is 48)
WALLS_OFF = "its most wanted pose would wall off a task object from the robot"  # a guarded step's reason
WALLS_OFF_DOOR = "its most wanted pose would wall off a task object or a door from the robot"  # a crossed room's


@dataclass
class Options:
    """The candidates of the current object that pass the hard filters, with their energy terms."""

    obj: PlanObject
    cands: np.ndarray  # (N, 3) every candidate of the object
    feasible: np.ndarray  # (M,) indices into cands
    terms: dict[str, np.ndarray]  # each (M,): energy of placed + candidate, remaining objects pending
    soft: np.ndarray  # (M,) the constraint score of candidates.CandidateScorer
    shared: Shared | None = None  # what the soft score and the energy computed for the feasible ones


def hard_filter(scorer: CandidateScorer, obj: PlanObject, placed: list[PlacedObject], cands: np.ndarray,
                swept: SweptBoxes, strict: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """(mask of the candidates passing the hard filters, squared overlap areas with the placed bodies summed
    in placed order: the collision term the vectorised energy computes for the same candidates). `swept`:
    the candidates' bodies. The same rules as `CandidateScorer.evaluate` (tested), with a sweep-and-prune
    broad phase instead of an all-pairs overlap matrix."""
    ok = np.ones(len(cands), bool)
    squared = np.zeros(len(cands))
    if not len(cands):
        return ok, squared

    def clear_of(swept: SweptBoxes, others, sq=None) -> None:
        ok[swept.overlapping(others, OVERLAP_TOL, sq)] = False

    clear_of(swept, [p.body for p in placed], squared)
    clear_of(swept, scorer.door_zones)
    if strict:
        problem = scorer.problem
        free = [p for p in placed if not problem.constraints.tied(obj.id, p.id)]
        if problem.clearance.get(obj.id, 0.0) > 0:
            inside, strips = scorer.strips(obj, cands, swept)
            ok &= inside
            clear_of(strips, [p.body for p in free])
        clear_of(swept, [p.front for p in free if p.front is not None])
    return ok, squared


class Episode:
    """Objects placed one at a time in `problem.order`; fixed poses are taken as they are."""

    def __init__(self, plan: ConstraintPlan, fixed: Fixed | None = None, first: Collection[str] = (),
                 shares: Episode | None = None):
        """`shares`: an episode of the same plan and kept poses (the first solve, to the second solves and the
        restarts) whose plan-only parts this one reuses instead of making them again: the problem read from the
        plan, the candidates' geometry (`CandidateScorer`'s caches) and the navigation grid of the reach tests."""
        if shares is None:
            self.problem = PlacementProblem.from_plan(plan, fixed, first)
            self.scorer = CandidateScorer(self.problem)
        else:
            self.problem = shares.problem.with_first(first)
            self.scorer = CandidateScorer(self.problem, like=shares.scorer)
            self.__dict__["reach"] = shares.reach  # the `reach` cached property, made already
        self.order = self.problem.order
        self.i = 0
        self.placed: list[PlacedObject] = []
        self.failed: dict[str, str] = {}
        self.energy = 0.0  # energy after the last step (objects still to come pending)
        self.terms: dict[str, float] = {}
        self.n = max(len(self.problem.plan.objects), 1)
        self._energy = CandidateEnergy(self.problem, [], pending=self.pending())  # updated step by step
        # the energy set-up a repair's last move or pass left, made when first asked (models.placement.polish.Standing)
        self.repaired: Callable[[], CandidateEnergy] | None = None

    @property
    def setup(self) -> CandidateEnergy:
        """The energy set-up of the objects placed by the steps so far (a repair's moves are not in it)."""
        return self._energy

    @cached_property
    def reach(self) -> Reach:
        return Reach(self.problem)

    @property
    def walls_off(self) -> str:
        """A guarded step's reason (a crossed room's doors are guarded too)."""
        return WALLS_OFF_DOOR if self.reach.gates else WALLS_OFF

    @property
    def done(self) -> bool:
        return self.i >= len(self.order)

    def pending(self) -> set[str]:
        return {o.id for o in self.order[self.i + 1:]}

    def options(self) -> Options:
        obj = self.order[self.i]
        if obj.id in self.problem.fixed:
            cands = np.array([self.problem.fixed[obj.id]], float)
            soft = np.zeros(1)
            feasible = np.array([0])
            terms = self._energy.score(obj, cands)
            return Options(obj, cands, feasible, terms, soft)
        # the candidates' boxes and their sweep structure serve the hard filter, the soft score and the energy
        cands, body = self.scorer.bodies(obj)
        swept = self.scorer.swept(obj)
        strict = True
        ok, squared = hard_filter(self.scorer, obj, self.placed, cands, swept, True)
        if not ok.any():  # relax the front-clearance rules before giving up
            strict = False
            ok, squared = hard_filter(self.scorer, obj, self.placed, cands, swept, False)
        feasible = np.flatnonzero(ok)
        if not len(feasible):
            return Options(obj, cands, feasible, {}, np.zeros(0))
        shared = Shared.of(cands[feasible], obj, body[feasible])
        shared.collision, shared.zones_clear = squared[feasible], strict
        soft = self.scorer.soft_scores(obj, cands[feasible], self.placed, shared)[0]
        terms = self._energy.score(obj, cands[feasible], shared=shared)
        return Options(obj, cands, feasible, terms, soft, shared)

    def apply(self, opts: Options, pick: int | None) -> float:
        """Place `opts.obj` at feasible candidate `pick` (None: it stays unplaced); the reward (energy drop)."""
        if pick is None:
            self.failed[opts.obj.id] = NO_ROOM
            self._energy = copy.copy(self._energy)
            self._energy.pending = {o.id for o in self.order[self.i + 2:]}
            after = self.energy + WEIGHTS["missing"] / self.n
            self.terms = {**self.terms, "missing": self.terms.get("missing", 0.0) + 1 / self.n}
        else:
            x, z, rot = (float(v) for v in opts.cands[opts.feasible[pick]])
            self.placed.append(self.scorer.place(opts.obj, x, z, rot))
            if opts.shared is not None:
                self._energy.remember(opts.shared, pick)
            self._energy = self._energy.after(self.placed[-1], pending={o.id for o in self.order[self.i + 2:]})
            self.terms = {k: float(v[pick]) for k, v in opts.terms.items()}
            after = self.terms["total"]
        reward = self.energy - after
        self.energy = after
        self.i += 1
        return reward

    def guarded(self, opts: Options, order: np.ndarray) -> int:
        """The reach guard, an action mask (not in the paper): of the feasible candidates `order` (indices into
        `opts.feasible`, most wanted first), the first of the `GUARD_TRIES` first whose placing leaves no more
        task objects out of the robot's reach (models.placement.reach); the most wanted if each of them walls
        one off. A step-wise placer's energy sees only the objects placed so far, so a pose that walls off an
        access strip can look best."""
        return int(self.first_kept(opts, order, 1)[0])

    def keeping(self, opts: Options, ks: np.ndarray) -> np.ndarray:
        """For each feasible candidate `ks` (indices into `opts.feasible`): does placing it leave no more task
        objects out of the robot's reach? The reach guard's test for every candidate at once (training's
        action mask, `agent.rollout`)."""
        return np.fromiter(self.reach.keeping(self.placed, self._poses(opts, ks), self.setup.blocked,
                                              self.setup.reach), bool, len(ks))

    def _poses(self, opts: Options, ks: np.ndarray):
        """The placed objects of the feasible candidates `ks`, made as they are asked for."""
        return (self.scorer.place(opts.obj, *(float(v) for v in opts.cands[opts.feasible[k]])) for k in ks)

    def fork(self) -> Episode:
        """An independent copy of this episode (its energy set-ups are immutable and are shared)."""
        twin = copy.copy(self)
        twin.placed, twin.failed = list(self.placed), dict(self.failed)
        return twin

    def finish_greedily(self) -> float:
        """Place the objects still to come at their lowest immediate energy; the final energy."""
        while not self.done:
            opts = self.options()
            self.apply(opts, int(np.argmin(steady(opts.terms["total"]))) if len(opts.feasible) else None)
        return self.energy

    def judge(self, opts: Options, picks: np.ndarray) -> np.ndarray:
        """For each feasible candidate `picks` (indices into `opts.feasible`) of this step: the final energy of
        the episode with it placed and the objects still to come placed greedily (a one-step look-ahead)."""
        finals = []
        for pick in picks:
            twin = self.fork()
            twin.apply(opts, int(pick))
            finals.append(twin.finish_greedily())
        return np.array(finals)

    def first_kept(self, opts: Options, order: np.ndarray, k: int) -> np.ndarray:
        """The first `k` of the feasible candidates `order` (most wanted first; at most `GUARD_TRIES` tried) whose
        placing leaves no more task objects out of the robot's reach; if none does, the first `k` (`guarded` is
        this with k = 1)."""
        tried = order[:GUARD_TRIES]
        kept = []
        for pick, ok in zip(tried, self.reach.keeping(self.placed, self._poses(opts, tried), self.setup.blocked,
                                                      self.setup.reach)):
            if ok:
                kept.append(int(pick))
                if len(kept) == k:
                    break
        return np.array(kept) if kept else order[:k]

    def step_record(self, opts: Options, pick: int | None, probs: np.ndarray, why: str = "") -> PlacementStep:
        """What the studio shows: `probs` (M,) over the feasible candidates; -inf for the rest."""
        scores = np.full(len(opts.cands), -np.inf)
        scores[opts.feasible] = probs
        pose = (None, None, None) if pick is None else tuple(float(v) for v in opts.cands[opts.feasible[pick]])
        return PlacementStep(opts.obj.id, *pose, opts.cands, scores, dict(self.terms), why)

    def layout(self, solver: str, seed: int, elapsed: float) -> Layout:
        poses = {p.id: (p.x, p.z, p.rotation) for p in self.placed}
        return make_layout(self.problem, poses, self.failed, solver, seed, elapsed,
                           default_reason="not reached")


class GreedySolver:
    name = "greedy"

    def __init__(self, repair: bool = True, guard: bool = True):
        """`repair`: finish with the repairs (models.placement.repair), as Plan2Place does; `guard`: the reach
        guard (`Episode.guarded`), as Plan2Place has."""
        self.repair, self.guard = repair, guard
        if not repair:
            self.name = "greedy, no repair"

    def solve(self, plan: ConstraintPlan, seed: int = 0, time_budget_s: float | None = None,
              observer: StepObserver | None = None, fixed: Fixed | None = None) -> Layout:
        start = time.perf_counter()
        ep = place_stepwise(plan, np.random.default_rng(seed), self._choose, fixed, observer, self.repair)
        return ep.layout(self.name, seed, time.perf_counter() - start)

    def _choose(self, ep: Episode, opts: Options, rng: np.random.Generator) -> tuple[int, np.ndarray, str]:
        total = tie_broken(opts, rng)
        pick, why = int(np.argmin(total)), ""
        if self.guard and pick != (guarded := ep.guarded(opts, np.argsort(total, kind="stable"))):
            pick, why = guarded, ep.walls_off
        probs = np.exp(-(total - total.min()) / 0.05)
        return pick, probs / probs.sum(), why


Choose = Callable[[Episode, Options, np.random.Generator], tuple[int, np.ndarray, str]]
Step = Callable[..., tuple[Episode, object, list[PlacementStep]]]  # backtrack.step's signature


def tie_broken(opts: Options, rng: np.random.Generator) -> np.ndarray:
    """The feasible candidates' immediate energies with a seeded tie-break added."""
    return opts.terms["total"] + rng.uniform(0, 1e-9, len(opts.feasible))


def place_stepwise(plan: ConstraintPlan, rng: np.random.Generator, choose: Choose, fixed: Fixed | None = None,
                   observer: StepObserver | None = None, repair: bool = True, keep_reach: bool = True,
                   exact: bool = False) -> Episode:
    """One episode of a step-wise placer (greedy, look-ahead, Plan2Place): at each step with a legal candidate,
    `choose(episode, options, rng)` gives (pick among the feasible candidates, probabilities for the heat-map, the
    step's reason); each step is observed; then, with `repair`, the repairs, the episode solved again with the
    objects of broken constraints first, if that is better (models.placement.reorder), and, with `keep_reach`,
    solved again with every task object kept reachable, if that is better (models.placement.reach_kept); each from
    the same random state. Where that leaves an object out, with `repair`, all of it again from another random
    state, if that is better (models.placement.restarts). Then, with `repair`, Z3 over the whole room where a
    constraint stays broken in a small room that meets most of its constraints (with `exact`, wherever one stays
    broken in a small room), if that is better (models.placement.exact_finish). All of it on one BLAS thread
    (models.placement.blas)."""
    with blas.one_blas_thread():
        start = copy.deepcopy(rng)
        ep = _solved(plan, rng, choose, fixed, observer, repair, keep_reach)
        if repair:
            from models.placement.exact_finish import MIN_MET, finished_exactly  # they build on this module's Episode
            from models.placement.restarts import drawn, restarted, salted
            solved = ep  # each restart shares its plan-only parts (`Episode`'s `shares`)
            ep = restarted(ep, lambda salt, seen: _solved(plan, salted(start, salt), drawn(choose), fixed, seen,
                                                          repair, keep_reach, solved), observer)
            ep = finished_exactly(ep, int(copy.deepcopy(start).integers(2**31)), observer, 0.0 if exact else MIN_MET)
    return ep


def _solved(plan: ConstraintPlan, rng: np.random.Generator, choose: Choose, fixed: Fixed | None,
            observer: StepObserver | None, repair: bool, keep_reach: bool, shares: Episode | None = None) -> Episode:
    """`place_stepwise`'s episode from the random state `rng`, without the restarts (`shares`: `Episode`'s)."""
    start = copy.deepcopy(rng)
    ep = _steps(plan, rng, choose, fixed, observer, (), shares)
    if repair:
        from models.placement.reach_kept import kept_step, solve_keeping  # they build on this module's Episode
        from models.placement.reorder import broken_first
        from models.placement.repair import repair as repair_layout
        first_solve = ep
        ep = broken_first(ep, repair_layout, lambda first, seen: _steps(plan, copy.deepcopy(start), choose, fixed,
                                                                         seen, first, first_solve), observer)
        if keep_reach:
            ep = solve_keeping(ep, repair_layout, lambda first, seen: _steps(
                plan, copy.deepcopy(start), choose, fixed, seen, first, first_solve, kept_step), observer)
    return ep


def _steps(plan: ConstraintPlan, rng: np.random.Generator, choose: Choose, fixed: Fixed | None,
           observer: StepObserver | None, first: Collection[str], shares: Episode | None = None,
           step: Step | None = None) -> Episode:
    """`place_stepwise`'s steps, with the objects of `first` placed as early as their targets allow (`shares`:
    `Episode`'s); each made by `step` (default: models.placement.backtrack's, where an object that finds no room
    may send the placer a few steps back)."""
    from models.placement import backtrack as bt  # it builds on this module's Episode
    ep, steps, step = Episode(plan, fixed, first, shares), bt.recent(), step or bt.step
    while not ep.done:
        ep, steps, records = step(ep, ep.options(), choose, rng, steps)
        for record in records if observer is not None else ():
            observer(record)
    return ep
