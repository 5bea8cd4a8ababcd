"""ConstraintPlan -> Layout: the placers, all behind one Solver interface."""

from models.placement.base import (ALL_OBJECTS, DEFAULT_SOLVER, EXACT_FINISH, SOLVERS, PlacementStep, Solver,
                                   StepObserver, UnknownSolver, get_solver)
from models.placement.problem import PlacementProblem

__all__ = ["ALL_OBJECTS", "DEFAULT_SOLVER", "EXACT_FINISH", "PlacementProblem", "PlacementStep", "SOLVERS", "Solver",
           "StepObserver", "UnknownSolver", "get_solver"]
