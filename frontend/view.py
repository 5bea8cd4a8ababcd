"""Drawing a scene into one browser tab's 3D view (viser scene handles).

AI2-THOR is left-handed (x right, y up, z forward); the browser's three.js is right-handed, so z is
negated on the way in, as in the GLB export, and the room looks as it will in AI2-THOR.
"""

from __future__ import annotations

import math

import numpy as np
import viser

from models.exports.glb import ROLE_COLOURS
from models.placement import PlacementStep
from models.scene.walls import wall_boxes
from models.values import Scene, SceneObject

HIGHLIGHT = (255, 215, 0)
FLOOR = (205, 195, 175)
WALL = (236, 236, 230)
ZONE = (80, 200, 120)


def world(x: float, y: float, z: float) -> tuple[float, float, float]:
    return (x, y, -z)


def yaw(rotation_deg: float) -> tuple[float, float, float, float]:
    """Quaternion (wxyz) of a Unity yaw seen in the z-negated frame: a turn about +y by -r."""
    half = math.radians(-rotation_deg) / 2
    return (math.cos(half), 0.0, math.sin(half), 0.0)


def rotation_of(wxyz) -> float:
    """Unity yaw (degrees) of a quaternion about +y in the z-negated frame."""
    w, _, y, _ = wxyz
    return (-math.degrees(2 * math.atan2(y, w))) % 360


def colour(role: str) -> tuple[int, int, int]:
    return tuple(ROLE_COLOURS.get(role, ROLE_COLOURS["context"])[:3])


class SceneView:
    """The 3D content of one tab: room shell, objects (clickable), markers and the candidate heat-map."""

    def __init__(self, scene_api: viser.SceneApi):
        self.api = scene_api
        self.api.set_up_direction("+y")
        self.objects: dict[str, viser.BoxHandle] = {}
        self.labels: dict[str, viser.LabelHandle] = {}
        self.on_pick = None  # callback(object id)

    def clear(self) -> None:
        self.api.reset()
        self.objects.clear()
        self.labels.clear()

    def draw_room(self, scene: Scene) -> None:
        room = scene.room
        self.api.add_box("/room/floor", color=FLOOR, dimensions=(room.width, 0.02, room.depth),
                         position=world(room.width / 2, -0.01, room.depth / 2))
        for w in wall_boxes(room):
            self.api.add_box(f"/room/{w.name}", color=WALL, dimensions=w.extents, position=world(*w.centre),
                             opacity=0.35)
        r = scene.robot_start
        self.api.add_cylinder("/markers/robot", radius=0.2, height=0.3, color=(40, 40, 40),
                              position=world(r.x, 0.15, r.z), wxyz=(math.cos(-math.pi / 4), math.sin(-math.pi / 4), 0, 0))
        self.api.add_label("/markers/robot/label", "robot start", position=(0, 0.0, 0.3))
        if scene.vr_anchor is not None:
            v = scene.vr_anchor
            self.api.add_box("/markers/vr-zone", color=ZONE, dimensions=(0.8, 0.01, 0.8), opacity=0.5,
                             position=world(v.x, 0.005, v.z), wxyz=yaw(v.rotation))
            self.api.add_label("/markers/vr-zone/label", "VR user stands here", position=(0, 0.05, 0))

    def draw_objects(self, scene: Scene, visible: set[str] | None = None) -> None:
        """Every object (or those in `visible`) as a box of its true size, coloured by role, with its label."""
        for obj in scene.objects:
            shown = visible is None or obj.id in visible
            self._box(obj, shown)
            for child in obj.children:
                self._box(child, shown)

    def _box(self, obj: SceneObject, shown: bool) -> None:
        handle = self.api.add_box(f"/objects/{obj.id}", color=colour(obj.role),
                                  dimensions=(obj.size.x, obj.size.y, obj.size.z), position=world(obj.x, obj.y, obj.z),
                                  wxyz=yaw(obj.rotation), visible=shown)
        self.labels[obj.id] = self.api.add_label(f"/objects/{obj.id}/label", f"{obj.id}",
                                                 position=(0, obj.size.y / 2 + 0.08, 0), visible=shown)
        handle.on_click(lambda _event, oid=obj.id: self.on_pick and self.on_pick(oid))
        self.objects[obj.id] = handle

    def drop_in(self, obj_id: str, scene: Scene, fraction: float) -> None:
        """Animate an object settling into place: `fraction` 0 is 0.8 m above, 1 is at rest.

        It is drawn in the highlight colour while it moves and takes its role colour when it lands.
        """
        obj = next((o for o in scene.all_objects() if o.id == obj_id), None)
        handle = self.objects.get(obj_id)
        if obj is None or handle is None:
            return
        if not handle.visible:  # first frame: show it, in the highlight colour
            handle.visible = True
            self.labels[obj_id].visible = True
            handle.color = HIGHLIGHT
        if fraction >= 1:
            handle.color = colour(obj.role)
        ease = 1 - (1 - fraction) ** 3
        handle.position = world(obj.x, obj.y + 0.8 * (1 - ease), obj.z)

    def heat_map(self, step: PlacementStep | None) -> None:
        """Candidate scores of one placement step as coloured points on the floor (best over rotations)."""
        if step is None or len(step.candidates) == 0:
            self.api.add_point_cloud("/heat", np.zeros((1, 3)), colors=(0, 0, 0), visible=False)
            return
        xz = step.candidates[:, :2]
        keys, inverse = np.unique(np.round(xz, 3), axis=0, return_inverse=True)
        best = np.full(len(keys), -np.inf)
        np.maximum.at(best, inverse.ravel(), step.scores)
        finite = np.isfinite(best)
        points = np.stack([keys[:, 0], np.full(len(keys), 0.015), -keys[:, 1]], axis=1)
        colours = np.tile(np.array([[90, 90, 90]], np.uint8), (len(keys), 1))
        if finite.any():
            v = best[finite]
            t = (v - v.min()) / max(float(v.max() - v.min()), 1e-9)
            colours[finite] = np.stack([255 * t, 60 + 120 * (1 - abs(t - 0.5) * 2), 255 * (1 - t)], axis=1).astype(np.uint8)
        self.api.add_point_cloud("/heat", points.astype(np.float32), colors=colours, point_size=0.07)
