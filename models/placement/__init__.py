"""ConstraintPlan -> Layout: the placers, all behind one Solver interface."""

from models.placement.base import SOLVERS, PlacementStep, Solver, StepObserver, UnknownSolver, get_solver
from models.placement.problem import PlacementProblem

__all__ = ["PlacementProblem", "PlacementStep", "SOLVERS", "Solver", "StepObserver", "UnknownSolver", "get_solver"]
