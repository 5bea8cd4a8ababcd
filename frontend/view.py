"""Drawing a scene into one browser tab's 3D view (viser scene handles).

AI2-THOR is left-handed (x right, y up, z forward); the browser's three.js is right-handed, so z is
negated on the way in, as in the GLB export, and the room looks as it will in AI2-THOR.

First render in a fresh tab is dominated by the browser compiling shaders (software WebGL here): the
view uses no environment map and no shadows, one mesh per object and one material kind, which took the
first Generate in a fresh tab from ~8 s to ~1 s (app/bench/studio.py measures it).
"""

from __future__ import annotations

import math

import numpy as np
import viser

from models.exports.glb import ROLE_COLOURS
from models.placement import PlacementStep
from models.scene.walls import wall_boxes
from models.shapes import shape_mesh
from models.values import Room, Scene, SceneObject

HIGHLIGHT = (255, 215, 0)
FLOOR = (205, 195, 175)
WALL = (236, 236, 230)
ZONE = (80, 200, 120)
PLAIN = {"cast_shadow": False, "receive_shadow": False}
LABEL_GAP = 0.16  # vertical step between labels that would overlap, metres
LABEL_NEAR = 0.9  # labels closer than this on the floor are stacked, metres
DROP = 0.8  # an object placed in the step animation drops in from this high, metres
LIFT = 0.3  # an object moved in the step animation is lifted this high on the way, metres


def world(x: float, y: float, z: float) -> tuple[float, float, float]:
    return (x, y, -z)


def yaw(rotation_deg: float) -> tuple[float, float, float, float]:
    """Quaternion (wxyz) of a Unity yaw seen in the z-negated frame: a turn about +y by -r."""
    half = math.radians(-rotation_deg) / 2
    return (math.cos(half), 0.0, math.sin(half), 0.0)


def colour(role: str) -> tuple[int, int, int]:
    return tuple(ROLE_COLOURS.get(role, ROLE_COLOURS["context"])[:3])


def tint(rgb, amount: float = 0.55) -> tuple[int, int, int]:
    return tuple(int(c + (h - c) * amount) for c, h in zip(rgb, HIGHLIGHT))


def label_layout(objects: list[SceneObject]) -> dict[str, tuple[float, int]]:
    """(height above the floor, stacking level) of each object's label: just above its top, raised a
    level at a time where labels of objects close together on the floor would be drawn over each other."""
    placed: list[tuple[float, float, float]] = []
    out = {}
    for o in sorted(objects, key=lambda o: (o.y + o.size.y / 2, o.x, o.z)):
        y, level = o.y + o.size.y / 2 + 0.08, 0
        while any(math.hypot(o.x - x, o.z - z) < LABEL_NEAR and abs(y - h) < LABEL_GAP - 1e-9
                  for x, z, h in placed):
            y, level = y + LABEL_GAP, level + 1
        placed.append((o.x, o.z, y))
        out[o.id] = (y, level)
    return out


def outline_segments(size) -> np.ndarray:
    """The 12 edges (12, 2, 3) of a box of `size` centred on the origin, slightly enlarged."""
    h = np.asarray(size, dtype=float) / 2 + 0.02
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * h
    edges = [(a, b) for a in range(8) for b in range(a + 1, 8) if bin(a ^ b).count("1") == 1]
    return np.array([[corners[a], corners[b]] for a, b in edges])


class SceneView:
    """The 3D content of one tab: room shell, objects (clickable shapes), labels, markers, the selection
    outline and the candidate heat-map."""

    def __init__(self, scene_api: viser.SceneApi):
        self.api = scene_api
        self.api.set_up_direction("+y")
        self.api.configure_environment_map(None)
        self.api.configure_default_lights(True, cast_shadow=False)
        # a soft sky/ground light, so faces turned away from the default lights are shaded, not black
        self.api.add_light_hemisphere("/lights/fill", sky_color=(255, 255, 255), ground_color=(160, 150, 140),
                                      intensity=1.2)
        self.nodes: list = []
        self.objects: dict[str, viser.MeshHandle] = {}
        self.labels: dict[str, viser.LabelHandle] = {}
        self.label_levels: dict[str, int] = {}
        self.top_view = False
        self.selected: str | None = None
        self.outline = None
        self.heat = None
        self.on_pick = None  # callback(object id)

    def clear(self) -> None:
        for handle in self.nodes + [self.heat]:
            _remove(handle)
        self.nodes.clear()
        self.objects.clear()
        self.labels.clear()
        self.outline = self.heat = None

    def _keep(self, handle):
        self.nodes.append(handle)
        return handle

    def draw_room(self, scene: Scene) -> None:
        self.draw_shell(scene.room)
        self.draw_markers(scene)

    def draw_shell(self, room: Room, x: float = 0.0, z: float = 0.0, name: str = "/room") -> None:
        """Floor and see-through walls of a room whose (0, 0) corner is at (x, z)."""
        self._keep(self.api.add_box(f"{name}/floor", color=FLOOR, dimensions=(room.width, 0.02, room.depth),
                                    position=world(x + room.width / 2, -0.01, z + room.depth / 2), **PLAIN))
        for w in wall_boxes(room):
            self._keep(self.api.add_box(f"{name}/{w.name}", color=WALL, dimensions=w.extents,
                                        position=world(w.centre[0] + x, w.centre[1], w.centre[2] + z), opacity=0.35,
                                        **PLAIN))

    def room_label(self, text: str, x: float, z: float) -> None:
        self._keep(self.api.add_label(f"/rooms/{text}", text, position=world(x, 2.9, z), anchor="bottom-center"))

    def draw_path(self, points: list[tuple[float, float]], rgb: tuple[int, int, int]) -> None:
        """The robot's walk as a line just above the floor."""
        if len(points) > 1:
            p = np.array([world(x, 0.05, z) for x, z in points], np.float32)
            self._keep(self.api.add_line_segments("/markers/path", np.stack([p[:-1], p[1:]], axis=1), colors=rgb,
                                                  thickness=4.0, thickness_units="screen"))

    def draw_markers(self, scene: Scene) -> None:
        """The robot's start and the VR user's spot."""
        r = scene.robot_start
        self._keep(self.api.add_cylinder("/markers/robot", radius=0.2, height=0.3, color=(40, 40, 40),
                                         position=world(r.x, 0.15, r.z), **PLAIN,
                                         wxyz=(math.cos(-math.pi / 4), math.sin(-math.pi / 4), 0, 0)))
        self.api.add_label("/markers/robot/label", "robot start", position=(0, 0.0, 0.3), anchor="bottom-center")
        if scene.vr_anchor is not None:
            v = scene.vr_anchor
            self._keep(self.api.add_box("/markers/vr-zone", color=ZONE, dimensions=(0.8, 0.01, 0.8), opacity=0.5,
                                        position=world(v.x, 0.005, v.z), wxyz=yaw(v.rotation), **PLAIN))
            self.api.add_label("/markers/vr-zone/label", "VR user", position=(0, 0.05, 0), anchor="bottom-center")

    def draw_objects(self, scene: Scene, visible: set[str] | None = None, labels: bool = True) -> None:
        """Every object (or those in `visible`) as its shape at its true size, coloured by role; labelled
        now or, with `labels=False`, when `draw_labels` is called (the first labels in a tab cost the
        browser a few hundred milliseconds, so a fresh scene is drawn first and labelled just after)."""
        for obj in scene.all_objects():
            self._shape(obj, visible is None or obj.id in visible)
        if labels:
            self.draw_labels(scene, visible)
        if self.selected in self.objects:
            self.select(self.selected, scene)

    def draw_labels(self, scene: Scene, visible: set[str] | None = None) -> None:
        layout = label_layout(scene.all_objects())
        for obj in scene.all_objects():
            if obj.id in self.objects:
                y, level = layout[obj.id]
                self.label_levels[obj.id] = level
                self.labels[obj.id] = self.api.add_label(
                    f"/objects/{obj.id}/label", obj.id, anchor=self._anchor(level), position=(0, y - obj.y, 0),
                    visible=visible is None or obj.id in visible)

    def _anchor(self, level: int) -> str:
        """Labels sit above their point; seen from straight above, heights no longer part stacked
        labels, so every other level hangs below its point instead."""
        return "top-center" if self.top_view and level % 2 else "bottom-center"

    def set_top_view(self, top: bool) -> None:
        self.top_view = top
        for oid, label in self.labels.items():
            label.anchor = self._anchor(self.label_levels.get(oid, 0))

    def _shape(self, obj: SceneObject, shown: bool) -> None:
        vertices, faces, _ = shape_mesh(obj.type, (obj.size.x, obj.size.y, obj.size.z))
        vertices = vertices * np.array([1, 1, -1], np.float32)  # into the z-negated frame...
        faces = faces[:, ::-1]  # ...which mirrors the winding
        handle = self._keep(self.api.add_mesh_simple(
            f"/objects/{obj.id}", vertices, faces, color=colour(obj.role), flat_shading=True, side="double",
            cast_shadow=False, receive_shadow=False, position=world(obj.x, obj.y, obj.z), wxyz=yaw(obj.rotation),
            visible=shown))
        handle.on_click(lambda _event, oid=obj.id: self.on_pick and self.on_pick(oid))
        self.objects[obj.id] = handle

    def move(self, obj: SceneObject) -> None:
        """Show an object at its (new) pose without redrawing the scene."""
        handle = self.objects.get(obj.id)
        if handle is not None:
            handle.position = world(obj.x, obj.y, obj.z)
            handle.wxyz = yaw(obj.rotation)

    def select(self, obj_id: str | None, scene: Scene) -> None:
        """Highlight one object: tinted and outlined (the outline follows the object); None clears."""
        if self.selected in self.objects:
            old = next((o for o in scene.all_objects() if o.id == self.selected), None)
            if old is not None:
                self.objects[self.selected].color = colour(old.role)
        _remove(self.outline)
        self.outline = None
        self.selected = obj_id
        obj = next((o for o in scene.all_objects() if o.id == obj_id), None)
        if obj is None or obj_id not in self.objects:
            return
        self.objects[obj_id].color = tint(colour(obj.role))
        segments = outline_segments((obj.size.x, obj.size.y, obj.size.z))
        self.outline = self.api.add_line_segments(f"/objects/{obj_id}/outline", segments, colors=HIGHLIGHT,
                                                  thickness=3.0, thickness_units="screen")

    def settle(self, obj: SceneObject, fraction: float, start: SceneObject | None = None) -> None:
        """Animate an object and what stands on it into their poses: `fraction` 0 is where they start, 1 at rest.
        Without `start` (it was not on show) it drops in from `DROP` above; else it slides from its pose in `start`,
        lifted up to `LIFT` on the way and turned halfway. It is drawn in the highlight colour while it moves and
        takes its role colour when it lands."""
        ease = 1 - (1 - fraction) ** 3
        froms = [start, *start.children] if start is not None else [None] * (1 + len(obj.children))
        for o, was in zip([obj, *obj.children], froms):
            handle = self.objects.get(o.id)
            if handle is None:
                continue
            if not handle.visible:
                handle.visible = True
                if o.id in self.labels:
                    self.labels[o.id].visible = True
            if was is None:
                position, turn = world(o.x, o.y + DROP * (1 - ease), o.z), o.rotation
            else:
                position = world(was.x + (o.x - was.x) * ease, o.y + LIFT * math.sin(math.pi * ease),
                                 was.z + (o.z - was.z) * ease)
                turn = o.rotation if ease >= 0.5 else was.rotation
            handle.position = position
            _set(handle, "color", colour(o.role) if fraction >= 1 else HIGHLIGHT)  # each change is a message
            _set(handle, "wxyz", yaw(turn))

    def hide(self, ids: set[str]) -> None:
        """Take objects (and their labels) off show: the room emptied for a solve from the start."""
        for oid in ids:
            for handle in (self.objects.get(oid), self.labels.get(oid)):
                if handle is not None:
                    handle.visible = False

    def heat_map(self, step: PlacementStep | None) -> None:
        """Candidate scores of one placement step as coloured points on the floor (best over rotations)."""
        if step is None or len(step.candidates) == 0:
            _remove(self.heat)
            self.heat = None
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
        self.heat = self.api.add_point_cloud("/heat", points.astype(np.float32), colors=colours, point_size=0.07)


def _set(handle, name: str, value) -> None:
    """Set a handle's property only if it changes (each change is a message to the browser)."""
    if not np.allclose(getattr(handle, name), value):
        setattr(handle, name, value)


def _remove(handle) -> None:
    """Remove a scene node unless it is gone already (children go with their parent)."""
    if handle is not None and not handle._impl.removed:
        handle.remove()
