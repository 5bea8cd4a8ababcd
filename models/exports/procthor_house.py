"""Scene -> ProcTHOR house JSON (schema 1.0.0), the dict AI2-THOR's `Controller(scene=house)` loads.

A single-room house: the room polygon, four room walls and their four exterior twins, doors and
windows cut into them (hole polygons in wall-local coordinates, measured from the wall's first
point), objects with real assetIds and their children, lights, and the agent's start pose.
"""

from __future__ import annotations

from models.scene.walls import wall_segments
from models.values import AgentPose, Opening, Room, Scene, SceneObject
from models.world import catalogue
from models.world.rooms import ROOM_SPECS

ROOM_ID = "room|1"
LAYER = "Procedural1"
GREY = {"r": 0.8, "g": 0.8, "b": 0.8}
AGENT_HEIGHT = 0.95


def _xyz(x: float, y: float, z: float) -> dict[str, float]:
    return {"x": round(float(x), 4), "y": round(float(y), 4), "z": round(float(z), 4)}


def _wall_id(owner: str, seg: tuple[float, float, float, float]) -> str:
    return f"wall|{owner}|" + "|".join(f"{v:.2f}" for v in seg)


def _walls(scene: Scene, height: float) -> list[dict]:
    room = scene.room
    return [wall_entry(_wall_id(owner, seg), ROOM_ID if owner == "1" else "exterior", seg, height, room.wall_material)
            for owner in ("1", "exterior") for seg in wall_segments(room.width, room.depth).values()]


def hole(hole_id: str, o: Opening, rooms: tuple[str, str], walls: tuple[str, str], centre: float) -> dict:
    """A door or window cut into wall0 (of room0) and its twin wall1 (of room1); `centre` is measured from
    the walls' first point."""
    bottom = o.sill or 0.0
    height = o.height or 2.0
    return {"id": hole_id, "assetId": o.asset_id, "room0": rooms[0], "room1": rooms[1],
            "wall0": walls[0], "wall1": walls[1],
            "holePolygon": [_xyz(centre - o.width / 2, bottom, 0), _xyz(centre + o.width / 2, bottom + height, 0)],
            "assetPosition": _xyz(centre, bottom + height / 2, 0)}


def _opening(kind: str, n: int, o: Opening, width: float, depth: float) -> dict:
    seg = wall_segments(width, depth)[o.wall]
    entry = hole(f"{kind}|1|{n}", o, (ROOM_ID, ROOM_ID), (_wall_id("1", seg), _wall_id("exterior", seg)), o.center)
    if kind == "door":
        entry.update(openable=True, openness=0)
    return entry


def thor_id(obj: SceneObject, child: bool, room: int = 1) -> str:
    """AI2-THOR style id: `Fridge|1|0` for `fridge-0` in room|1, `Bread|surface|1|0` for a child."""
    n = obj.id.rsplit("-", 1)[-1]
    return f"{obj.type}|surface|{room}|{n}" if child else f"{obj.type}|{room}|{n}"


def thor_object(obj: SceneObject, child: bool = False, room: int = 1) -> dict:
    cat = catalogue()
    entry = {"id": thor_id(obj, child, room), "assetId": obj.asset_id, "position": _xyz(obj.x, obj.y, obj.z),
             "rotation": _xyz(0, obj.rotation, 0),
             "kinematic": not child and not (obj.type in cat and cat.host(obj.type).pickupable),
             "layer": LAYER}
    if not child:
        entry["material"] = None
        entry["children"] = [thor_object(c, child=True, room=room) for c in obj.children]
    return entry


def room_entry(room_id: str, room: Room, corners: list[tuple[float, float]]) -> dict:
    return {"id": room_id, "roomType": ROOM_SPECS[room.type].procthor_type,
            "floorPolygon": [_xyz(x, 0, z) for x, z in corners],
            "floorMaterial": {"name": room.floor_material or "OakFloor"}, "ceilings": [], "children": [],
            "layer": LAYER}


def wall_entry(wall_id: str, room_id: str, seg: tuple[float, float, float, float], height: float,
               material: str | None) -> dict:
    x0, z0, x1, z1 = seg
    return {"id": wall_id, "roomId": room_id,
            "polygon": [_xyz(x0, 0, z0), _xyz(x1, 0, z1), _xyz(x0, height, z0), _xyz(x1, height, z1)],
            "material": {"name": material or "PureWhite", "color": GREY}, "color": GREY, "layer": LAYER}


def point_light(light_id: str, x: float, y: float, z: float) -> dict:
    return {"id": light_id, "type": "point", "intensity": 0.45, "range": 15, "layer": LAYER,
            "position": _xyz(x, y, z),
            "rgb": {"r": 1.0, "g": 0.855, "b": 0.722}, "cullingMaskOff": ["Procedural0", "Procedural2", "Procedural3"],
            "shadow": {"type": "Soft", "strength": 1, "normalBias": 0, "bias": 0.05, "nearPlane": 0.2,
                       "resolution": "FromQualitySettings"}}


def procedural_parameters(lights: list[dict]) -> dict:
    return {
        "ceilingColor": GREY, "ceilingMaterial": {"name": "PureWhite", "color": GREY},
        "floorColliderThickness": 1.0, "receptacleHeight": 0.7, "reflections": [], "skyboxId": "SkyOakland",
        "lights": [
            {"id": "DirectionalLight", "type": "directional", "intensity": 1, "indirectMultiplier": 1.0,
             "position": _xyz(0.84, 0.1855, -1.09), "rotation": _xyz(66, 75, 0), "rgb": {"r": 1.0, "g": 1.0, "b": 1.0},
             "shadow": {"type": "Soft", "strength": 1, "normalBias": 0, "bias": 0, "nearPlane": 0.2,
                        "resolution": "FromQualitySettings"}},
            *lights,
        ],
    }


def metadata(pose: AgentPose, room_spec_id: str) -> dict:
    agent = {"horizon": pose.horizon, "position": _xyz(pose.x, AGENT_HEIGHT, pose.z),
             "rotation": _xyz(0, pose.rotation, 0), "standing": True}
    return {"agent": agent, "agentPoses": {k: dict(agent) for k in ("arm", "default", "locobot", "stretch")},
            "roomSpecId": room_spec_id, "schema": "1.0.0", "warnings": {}}


def to_house(scene: Scene) -> dict:
    room = scene.room
    height = room.wall_height or 2.6
    corners = [(0, 0), (0, room.depth), (room.width, room.depth), (room.width, 0)]
    return {
        "rooms": [room_entry(ROOM_ID, room, corners)],
        "walls": _walls(scene, height),
        "doors": [_opening("door", i, d, room.width, room.depth) for i, d in enumerate(room.doors)],
        "windows": [_opening("window", i, w, room.width, room.depth) for i, w in enumerate(room.windows)],
        "objects": [thor_object(o) for o in scene.objects],
        "proceduralParameters": procedural_parameters(
            [point_light("light_1", room.width / 2, height - 0.2, room.depth / 2)]),
        "metadata": metadata(scene.robot_start, f"h3ds-{room.type.replace(' ', '-')}"),
    }
