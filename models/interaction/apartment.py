"""What the headset side needs with an apartment: the robot's plan on the whole house, the VR start pose in
the anchor's room, and the haptic profiles of every room's objects, all keyed by the house JSON's ids
(`Fridge|<room number>|0`) and in the house frame."""

from __future__ import annotations

from models.interaction.haptics import haptic_profiles
from models.interaction.robot_plan import house_roles, plan_on_house
from models.interaction.vr_pose import vr_start_pose
from models.scene.apartment import house_pose
from models.values.apartment import Apartment
from models.values.interaction import HapticProfile, RobotPlan, VRPoseChoice


def apartment_robot_plan(apartment: Apartment, house: dict, force_action: bool = True) -> RobotPlan:
    """The task's plan on the apartment's exported house: through the doors, room by room."""
    roles = {k: v for hr, scene in zip(apartment.floorplan.rooms, apartment.scenes)
             for k, v in house_roles(scene, hr.number).items()}
    return plan_on_house(house, apartment.task_graph, roles, force_action)


def apartment_vr_pose(apartment: Apartment) -> VRPoseChoice:
    """The single-room choice in the anchor's room, moved into the house frame."""
    rooms = apartment.floorplan.rooms
    k = next((i for i, hr in enumerate(rooms) if hr.id == apartment.anchor_room), None)
    if k is None:
        return VRPoseChoice(reasons=["the task's anchor is in no room of the apartment"])
    choice = vr_start_pose(apartment.scenes[k], apartment.task_graph)
    return choice.model_copy(update={
        "best": house_pose(choice.best, rooms[k]) if choice.best else None,
        "alternatives": [c.model_copy(update={"pose": house_pose(c.pose, rooms[k])}) for c in choice.alternatives]})


def apartment_haptic_profiles(apartment: Apartment) -> list[HapticProfile]:
    return [p for hr, scene in zip(apartment.floorplan.rooms, apartment.scenes)
            for p in haptic_profiles(scene, hr.number)]

