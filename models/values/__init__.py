"""The typed values that flow through the pipeline, one module per stage.

instruction -> TaskGraph -> RoomPlan -> ConstraintPlan -> Layout -> Scene -> exports
"""

from models.values.common import Provenance, Size
from models.values.constraint_plan import ConstraintPlan, PlanObject
from models.values.layout import Layout, Placement, Timing, Unplaced
from models.values.room import Opening, Room
from models.values.room_plan import RoomPlan, SurfaceObject
from models.values.scene import AgentPose, Scene, SceneObject
from models.values.task_graph import ROLES, TASK_TYPES, TaskGraph, TaskObject

__all__ = [
    "AgentPose", "ConstraintPlan", "Layout", "Opening", "Placement", "PlanObject", "Provenance", "ROLES",
    "Room", "RoomPlan", "Scene", "SceneObject", "Size", "SurfaceObject", "TASK_TYPES", "TaskGraph",
    "TaskObject", "Timing", "Unplaced",
]
