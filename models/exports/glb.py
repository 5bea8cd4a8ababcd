"""Scene -> binary glTF (GLB) with trimesh: floor, walls with door and window openings, and every
object as its procedural low-poly shape (models.shapes, the same triangles the studio draws) at its true
size, coloured by role (secondary parts darker) and named by its id (Blender's outliner shows them).

glTF is right-handed and AI2-THOR (Unity) left-handed, so z is negated on the way out; the scene
looks the same as in AI2-THOR instead of mirrored.
"""

from __future__ import annotations

import numpy as np
import trimesh

from models.scene.walls import wall_boxes
from models.shapes import shape_mesh
from models.values import Room, Scene, SceneObject

ROLE_COLOURS = {"anchor": (220, 60, 60, 255), "key": (240, 160, 40, 255), "inference": (60, 120, 220, 255),
                "context": (170, 170, 170, 255)}
FLOOR_COLOUR = (200, 190, 170, 255)
WALL_COLOUR = (235, 235, 230, 255)
UNITY_TO_GLTF = np.diag([1.0, 1.0, -1.0, 1.0])


def _placed(mesh: trimesh.Trimesh, centre, yaw_deg: float, name: str) -> trimesh.Trimesh:
    r = np.radians(yaw_deg)  # Unity yaw: front (sin r, cos r); a turn about +y in left-handed axes
    rot = np.array([[np.cos(r), 0, np.sin(r), 0], [0, 1, 0, 0], [-np.sin(r), 0, np.cos(r), 0], [0, 0, 0, 1]])
    move = np.eye(4)
    move[:3, 3] = centre
    mesh.apply_transform(move @ rot)
    mesh.metadata["name"] = name
    return mesh


def _box(extents, centre, yaw_deg: float, colour, name: str) -> trimesh.Trimesh:
    mesh = trimesh.creation.box(extents=extents)
    mesh.visual.face_colors = colour
    return _placed(mesh, centre, yaw_deg, name)


def _shape(obj: SceneObject, colour) -> trimesh.Trimesh:
    """The object's procedural shape; faces coloured by role, darker for legs and trims."""
    vertices, faces, shades = shape_mesh(obj.type, (obj.size.x, obj.size.y, obj.size.z))
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    rgb = np.clip(np.outer(shades, colour[:3]), 0, 255)
    mesh.visual.face_colors = np.column_stack([rgb, np.full(len(faces), colour[3])]).astype(np.uint8)
    return _placed(mesh, (obj.x, obj.y, obj.z), obj.rotation, obj.id)


def _room_meshes(room: Room, x: float = 0.0, z: float = 0.0, prefix: str = "") -> list[trimesh.Trimesh]:
    """The floor and the walls of a room whose (0, 0) corner is at (x, z)."""
    meshes = [_box((room.width, 0.02, room.depth), (x + room.width / 2, -0.01, z + room.depth / 2), 0,
                   FLOOR_COLOUR, prefix + "floor")]
    return meshes + [_box(w.extents, (w.centre[0] + x, w.centre[1], w.centre[2] + z), 0, WALL_COLOUR, prefix + w.name)
                     for w in wall_boxes(room)]


def _object_meshes(obj: SceneObject) -> list[trimesh.Trimesh]:
    colour = ROLE_COLOURS.get(obj.role, ROLE_COLOURS["context"])
    meshes = [_shape(obj, colour)]
    for child in obj.children:
        meshes += _object_meshes(child)
    return meshes


def _gltf_scene(meshes: list[trimesh.Trimesh]) -> trimesh.Scene:
    out = trimesh.Scene()
    for mesh in meshes:
        mesh.apply_transform(UNITY_TO_GLTF)
        out.add_geometry(mesh, node_name=mesh.metadata["name"], geom_name=mesh.metadata["name"])
    return out


def to_trimesh_scene(scene: Scene) -> trimesh.Scene:
    meshes = _room_meshes(scene.room)
    for obj in scene.objects:
        meshes += _object_meshes(obj)
    return _gltf_scene(meshes)


def house_glb(rooms: list[tuple[Room, float, float, str]], objects: list[SceneObject]) -> bytes:
    """Several rooms (room, x, z of its corner, name prefix) and their objects, all in the house frame."""
    meshes = [m for room, x, z, prefix in rooms for m in _room_meshes(room, x, z, prefix)]
    for obj in objects:
        meshes += _object_meshes(obj)
    return _gltf_scene(meshes).export(file_type="glb")


def to_glb(scene: Scene) -> bytes:
    return to_trimesh_scene(scene).export(file_type="glb")
