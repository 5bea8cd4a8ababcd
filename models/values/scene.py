"""Scene: the placed room with real assets, ready for AI2-THOR, the GLB viewer and the headset."""

from __future__ import annotations

from pydantic import Field

from models.values.common import Provenance, Size, Value
from models.values.layout import Unplaced
from models.values.room import Room
from models.values.room_plan import RoomPlan
from models.values.task_graph import TaskGraph


class SceneObject(Value):
    """An object with its asset; (x, y, z) is the centre of its bounding box, y up."""

    id: str
    type: str
    asset_id: str
    role: str
    x: float
    y: float
    z: float
    rotation: float
    size: Size
    children: list[SceneObject] = Field(default_factory=list)


class AgentPose(Value):
    x: float
    z: float
    rotation: float
    horizon: float = 30.0


class Scene(Value):
    id: str
    room: Room
    task_graph: TaskGraph | None = None
    objects: list[SceneObject]
    unplaced: list[Unplaced] = Field(default_factory=list)
    robot_start: AgentPose
    vr_anchor: AgentPose | None = None  # where the VR user starts (models.interaction.vr_start_pose's best)
    vr_alternatives: list[AgentPose] = Field(default_factory=list)  # the other valid VR poses, best first
    warnings: list[str] = Field(default_factory=list)
    provenance: list[Provenance] = Field(default_factory=list)
    # what the scene was made from, so that a stored version can be re-opened and edited
    room_plan: RoomPlan | None = None
    constraints: str | None = None

    def all_objects(self) -> list[SceneObject]:
        out = []
        for o in self.objects:
            out.append(o)
            out.extend(o.children)
        return out
