"""What a scene push carries for a stored scene of either kind: the house JSON, the robot's plan on it, the
VR start pose and the haptic profiles (an apartment's are the whole house's, in the house frame)."""

from __future__ import annotations

from dataclasses import dataclass

from models.exports.stored import house_of
from models.interaction import haptic_profiles, robot_plan, vr_start_pose
from models.interaction.apartment import apartment_haptic_profiles, apartment_robot_plan, apartment_vr_pose
from models.values.apartment import Apartment
from models.values.interaction import HapticProfile, RobotPlan, VRPoseChoice
from studio_db.store import Stored


@dataclass(frozen=True)
class PushContent:
    house: dict
    plan: RobotPlan
    vr_start_pose: VRPoseChoice
    haptic_profiles: list[HapticProfile]


def push_content(value: Stored) -> PushContent:
    house = house_of(value)
    if isinstance(value, Apartment):
        return PushContent(house, apartment_robot_plan(value, house), apartment_vr_pose(value),
                           apartment_haptic_profiles(value))
    return PushContent(house, robot_plan(value, house), vr_start_pose(value), haptic_profiles(value))
