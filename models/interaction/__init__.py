"""What the headset side needs with a scene: the VR start pose, haptic profiles per object, and the robot's
task plan as AI2-THOR actions with a symbolic checker (ALFRED's state tracking and goal conditions)."""

from models.interaction.vr_pose import vr_start_pose  # first: models.scene imports it
from models.interaction.haptics import haptic_class, haptic_profiles, profile_for, readme_table, state_class
from models.interaction.robot_plan import approach_pose, check_plan, goal_conditions, robot_plan
from models.interaction.symbolic import ActionError, ObjectState, SymbolicState, execute_step
from models.values.interaction import (
    GLOVE_MOTORS,
    ColourTransition,
    HapticProfile,
    MotorPattern,
    PlanCheck,
    PlanStep,
    RobotPlan,
    StepResult,
    VRCandidate,
    VRPoseChoice,
)

__all__ = [
    "ActionError", "ColourTransition", "GLOVE_MOTORS", "HapticProfile", "MotorPattern", "ObjectState", "PlanCheck",
    "PlanStep", "RobotPlan", "StepResult", "SymbolicState", "VRCandidate", "VRPoseChoice", "approach_pose",
    "check_plan", "execute_step", "goal_conditions", "haptic_class", "haptic_profiles", "profile_for",
    "readme_table", "robot_plan", "state_class", "vr_start_pose",
]
