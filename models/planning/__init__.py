"""TaskGraph -> RoomPlan -> ConstraintPlan: the room shell, the objects in it, and their constraints."""

from models.planning.constraint_writer import ConstraintWriter
from models.planning.room_planner import RoomPlanner, RoomPlannerSettings

__all__ = ["ConstraintWriter", "RoomPlanner", "RoomPlannerSettings"]
