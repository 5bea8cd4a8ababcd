"""The one interface every placer implements, and the registry the CLI, API and studio choose from."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from models.errors import InputError
from models.values import ConstraintPlan, Layout


@dataclass(frozen=True)
class PlacementStep:
    """What a placer did for one object: shown step by step in the studio."""

    object_id: str
    x: float | None
    z: float | None
    rotation: float | None
    candidates: np.ndarray  # (N, 3): x, z, rotation of every candidate considered
    scores: np.ndarray  # (N,) higher is better; -inf for candidates that fail a hard filter
    terms: dict[str, float]  # energy terms of the chosen pose
    why: str = ""  # a repair's reason for moving an object placed before, or the reach guard's for not taking
    # the placer's most wanted pose (empty: the placer's own choice)
    restart: bool = False  # the first step of the room solved again from empty (models.placement.reorder): what was
    # placed before it is taken up


StepObserver = Callable[[PlacementStep], None]
Fixed = dict[str, tuple[float, float, float]]


class Solver(Protocol):
    name: str

    def solve(self, plan: ConstraintPlan, seed: int = 0, time_budget_s: float | None = None,
              observer: StepObserver | None = None, fixed: Fixed | None = None) -> Layout:
        """Place the plan's objects; `fixed` poses (object id -> x, z, rotation) are kept as they are."""


class UnknownSolver(InputError):
    def __init__(self, name: str):
        super().__init__(f"unknown solver {name!r}; available: {', '.join(sorted(SOLVERS))}")


def _dfs() -> Solver:
    """A depth-first search over grid poses in the manner of Holodeck's (baseline)."""
    from models.placement.dfs import DFSSolver
    return DFSSolver()


def _milp() -> Solver:
    """Holodeck's MILP formulation solved with HiGHS, object by object (baseline)."""
    from models.placement.milp import MILPSolver
    return MILPSolver()


def _milp_whole() -> Solver:
    """The monolithic MILP, one model for all objects (kept to measure the object-by-object one against)."""
    from models.placement.milp import MILPSolver
    return MILPSolver(mode="whole")


def _z3() -> Solver:
    """The same model stated as logic for Z3's optimiser, all objects at once (baseline; slow)."""
    from models.placement.smt import Z3Solver
    return Z3Solver()


def _greedy() -> Solver:
    """Per object, the candidate of lowest immediate energy, then the repairs (the learning's yardstick)."""
    from models.placement.greedy import GreedySolver
    return GreedySolver()


def _lookahead() -> Solver:
    """Greedy's best candidates judged by finishing the episode greedily, then the repairs (4-7 x slower)."""
    from models.placement.lookahead import LookaheadSolver
    return LookaheadSolver()


def _plan2place() -> Solver:
    """The trained actor-critic placer, then the repairs; may leave out what cuts a task object off (default)."""
    from models.placement.plan2place.solver import Plan2PlaceSolver
    return Plan2PlaceSolver()


ALL_OBJECTS = "plan2place_all_objects"  # the default without the reach-kept solve


def _plan2place_all_objects() -> Solver:
    """Plan2Place placing every object it legally can, even one that cuts a task object off from the robot.

    It is the default without the reach-kept solve (models.placement.reach_kept), which leaves such an object out
    in a crowded room when the energy finds that better."""
    from models.placement.plan2place.solver import Plan2PlaceSolver
    return Plan2PlaceSolver(keep_reach=False, name=ALL_OBJECTS)


EXACT_FINISH = "plan2place_exact"  # the default finished by Z3 wherever a constraint stays broken in a small room


def _plan2place_exact() -> Solver:
    """Plan2Place, asking Z3 over a small room wherever a constraint stays broken, even where most are (slower there).

    The default's repairs ask Z3 only where the layout meets at least 60 % of its constraints: where it met fewer, Z3
    took its whole budget and found a better layout in none of 88 runs (models.placement.exact_finish)."""
    from models.placement.plan2place.solver import Plan2PlaceSolver
    return Plan2PlaceSolver(exact=True, name=EXACT_FINISH)


def _plan2place_untrained() -> Solver:
    """The Plan2Place network at its initial weights (what training adds is measured against it)."""
    from models.placement.plan2place.solver import untrained_solver
    return untrained_solver()


SOLVERS: dict[str, Callable[[], Solver]] = {"greedy": _greedy, "lookahead": _lookahead, "plan2place": _plan2place,
                                            ALL_OBJECTS: _plan2place_all_objects, EXACT_FINISH: _plan2place_exact,
                                            "plan2place_untrained": _plan2place_untrained, "dfs": _dfs, "milp": _milp,
                                            "milp_whole": _milp_whole, "z3": _z3}
DEFAULT_SOLVER = "plan2place"


def summaries() -> dict[str, str]:
    """Each solver's name and one line on what it does (its factory's docstring's first line)."""
    return {name: next(iter((make.__doc__ or "").strip().splitlines()), "") for name, make in sorted(SOLVERS.items())}


def get_solver(name: str | None = None) -> Solver:
    key = (name or DEFAULT_SOLVER).strip().lower()
    if key not in SOLVERS:
        raise UnknownSolver(name or "")
    return SOLVERS[key]()
