"""The constraint language (Holodeck's floor-object vocabulary), its text format and its evaluator."""

from models.constraints.holodeck_text import read_constraints, write_constraints
from models.constraints.language import GLOBALS, RELATIONS, Constraint, ConstraintSet, ObjectConstraints

__all__ = ["GLOBALS", "RELATIONS", "Constraint", "ConstraintSet", "ObjectConstraints", "read_constraints",
           "write_constraints"]
