"""Scene -> ProcTHOR house JSON (schema 1.0.0), the dict AI2-THOR's `Controller(scene=house)` loads.

A single-room house: the room polygon, four room walls and their four exterior twins, doors and
windows cut into them (hole polygons in wall-local coordinates, measured from the wall's first
point), objects with real assetIds and their children, lights, and the agent's start pose.
"""

from __future__ import annotations

from models.scene.walls import wall_segments
from models.values import Opening, Scene, SceneObject
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
    material = {"name": room.wall_material or "PureWhite", "color": GREY}
    out = []
    for owner in ("1", "exterior"):
        for seg in wall_segments(room.width, room.depth).values():
            x0, z0, x1, z1 = seg
            out.append({"id": _wall_id(owner, seg), "roomId": ROOM_ID if owner == "1" else "exterior",
                        "polygon": [_xyz(x0, 0, z0), _xyz(x1, 0, z1), _xyz(x0, height, z0), _xyz(x1, height, z1)],
                        "material": material, "color": GREY, "layer": LAYER})
    return out


def _opening(kind: str, n: int, o: Opening, width: float, depth: float) -> dict:
    seg = wall_segments(width, depth)[o.wall]
    bottom = o.sill or 0.0
    height = o.height or 2.0
    entry = {"id": f"{kind}|1|{n}", "assetId": o.asset_id, "room0": ROOM_ID, "room1": ROOM_ID,
             "wall0": _wall_id("1", seg), "wall1": _wall_id("exterior", seg),
             "holePolygon": [_xyz(o.center - o.width / 2, bottom, 0), _xyz(o.center + o.width / 2, bottom + height, 0)],
             "assetPosition": _xyz(o.center, bottom + height / 2, 0)}
    if kind == "door":
        entry.update(openable=True, openness=0)
    return entry


def thor_id(obj: SceneObject, child: bool) -> str:
    """AI2-THOR style id: `Fridge|1|0` for `fridge-0`, `Bread|surface|1|0` for a child."""
    n = obj.id.rsplit("-", 1)[-1]
    return f"{obj.type}|surface|1|{n}" if child else f"{obj.type}|1|{n}"


def _object(obj: SceneObject, child: bool = False) -> dict:
    cat = catalogue()
    entry = {"id": thor_id(obj, child), "assetId": obj.asset_id, "position": _xyz(obj.x, obj.y, obj.z),
             "rotation": _xyz(0, obj.rotation, 0),
             "kinematic": not child and not (obj.type in cat and cat.host(obj.type).pickupable),
             "layer": LAYER}
    if not child:
        entry["material"] = None
        entry["children"] = [_object(c, child=True) for c in obj.children]
    return entry


def _agent(scene: Scene) -> dict:
    pose = scene.robot_start
    return {"horizon": pose.horizon, "position": _xyz(pose.x, AGENT_HEIGHT, pose.z),
            "rotation": _xyz(0, pose.rotation, 0), "standing": True}


def to_house(scene: Scene) -> dict:
    room = scene.room
    height = room.wall_height or 2.6
    corners = [(0, 0), (0, room.depth), (room.width, room.depth), (room.width, 0)]
    agent = _agent(scene)
    return {
        "rooms": [{"id": ROOM_ID, "roomType": ROOM_SPECS[room.type].procthor_type,
                   "floorPolygon": [_xyz(x, 0, z) for x, z in corners],
                   "floorMaterial": {"name": room.floor_material or "OakFloor"}, "ceilings": [], "children": [],
                   "layer": LAYER}],
        "walls": _walls(scene, height),
        "doors": [_opening("door", i, d, room.width, room.depth) for i, d in enumerate(room.doors)],
        "windows": [_opening("window", i, w, room.width, room.depth) for i, w in enumerate(room.windows)],
        "objects": [_object(o) for o in scene.objects],
        "proceduralParameters": {
            "ceilingColor": GREY, "ceilingMaterial": {"name": "PureWhite", "color": GREY},
            "floorColliderThickness": 1.0, "receptacleHeight": 0.7, "reflections": [], "skyboxId": "SkyOakland",
            "lights": [
                {"id": "DirectionalLight", "type": "directional", "intensity": 1, "indirectMultiplier": 1.0,
                 "position": _xyz(0.84, 0.1855, -1.09), "rotation": _xyz(66, 75, 0), "rgb": {"r": 1.0, "g": 1.0, "b": 1.0},
                 "shadow": {"type": "Soft", "strength": 1, "normalBias": 0, "bias": 0, "nearPlane": 0.2,
                            "resolution": "FromQualitySettings"}},
                {"id": "light_1", "type": "point", "intensity": 0.45, "range": 15, "layer": LAYER,
                 "position": _xyz(room.width / 2, height - 0.2, room.depth / 2),
                 "rgb": {"r": 1.0, "g": 0.855, "b": 0.722}, "cullingMaskOff": ["Procedural0", "Procedural2", "Procedural3"],
                 "shadow": {"type": "Soft", "strength": 1, "normalBias": 0, "bias": 0.05, "nearPlane": 0.2,
                            "resolution": "FromQualitySettings"}},
            ],
        },
        "metadata": {"agent": agent, "agentPoses": {k: dict(agent) for k in ("arm", "default", "locobot", "stretch")},
                     "roomSpecId": f"h3ds-{room.type.replace(' ', '-')}", "schema": "1.0.0", "warnings": {}},
    }
