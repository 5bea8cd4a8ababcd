"""Values the headset side receives with a scene: the VR start pose, haptic profiles and the robot's plan,
and what the symbolic checker says about the plan (models/interaction computes them)."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import Field

from models.values.common import Value
from models.values.scene import AgentPose

HapticClass = Literal["hot", "cold", "light", "normal"]
# The six motors of a bHaptics TactGlove, in the order of the int[] PlayMotors takes.
GLOVE_MOTORS: tuple[str, ...] = ("thumb", "index", "middle", "ring", "little", "wrist")


class VRCandidate(Value):
    """One valid place for the person to stand, with what made it valid."""

    pose: AgentPose
    distance_to_room_centre: float
    distance_to_anchor_front: float  # metres from the person's centre to the anchor's usable face
    angle: float  # direction of the candidate seen from the anchor's centre, degrees (0 = +z)


class VRPoseChoice(Value):
    """The VR start pose: the best candidate, the ranked valid ones (best first) and, when none is valid,
    why each rejected candidate failed."""

    anchor_id: str | None = None
    radius: float | None = None  # of the circle the valid poses are on (the last one tried when none is)
    best: AgentPose | None = None
    alternatives: list[VRCandidate] = Field(default_factory=list)
    candidates_tried: int = 0
    rejected: dict[str, int] = Field(default_factory=dict)  # reason -> how many candidates it rejected
    reasons: list[str] = Field(default_factory=list)


class MotorPattern(Value):
    """One PlayMotors call: intensities 0-100 for the glove's six motors (GLOVE_MOTORS order), repeated
    `pulses` times with `gap_ms` of silence between."""

    intensities: list[int] = Field(min_length=6, max_length=6)
    duration_ms: int = Field(gt=0)
    pulses: int = Field(default=1, ge=1)
    gap_ms: int = Field(default=0, ge=0)


class ColourTransition(Value):
    """The glove's tint while holding the object: from `start` to `end` (linear RGB 0-1) over duration_ms."""

    start: tuple[float, float, float]
    end: tuple[float, float, float]
    duration_ms: int = Field(ge=0)
    name: str


class HapticProfile(Value):
    object_id: str  # the id in the exported house (what AI2-THOR and Unity call the object)
    scene_object_id: str  # the id in the Scene
    object_type: str
    haptic_class: HapticClass
    touch: MotorPattern  # hover: a fingertip meets the object
    grasp: MotorPattern  # select: the hand closes on it
    colour: ColourTransition
    why: str  # which AI2-THOR properties gave the class


class PlanStep(Value):
    """One AI2-THOR action (`action` is passed to controller.step(**action) as is) and what it is for."""

    index: int
    action: dict[str, Any]
    description: str
    target: str | None = None  # house id the step is about (for TeleportFull: the object walked to)


class RobotPlan(Value):
    task_type: str
    instruction: str
    steps: list[PlanStep]
    objects: dict[str, str] = Field(default_factory=dict)  # task role (target, receptacle, fridge...) -> house id
    problems: list[str] = Field(default_factory=list)  # why the plan cannot reach the goal, if it cannot


class StepResult(Value):
    index: int
    action: str
    ok: bool
    message: str
    state: dict[str, Any] = Field(default_factory=dict)  # the symbolic state's summary after the step


class PlanCheck(Value):
    ok: bool
    goal: str
    steps: list[StepResult]
    failure: str | None = None
    goal_conditions: dict[str, bool] = Field(default_factory=dict)
