"""The picked object's panel above the tabs, the drag gizmo on its top, and the designer's moves: drags, typed poses,
turns, carrying an object to another room of an apartment, and re-placing the rest around the moves."""

from __future__ import annotations

import time
from dataclasses import replace

from app.editing import move_row
from app.pipeline import pose_of
from frontend.view import world
from models.values.edit import Edit
from models.world import catalogue

LIVE_RESCORE_S = 0.3  # while dragging, the checks re-run at most this often


class PickingPanel:
    def __init__(self, session, gui):
        self.session = session
        self.selected: str | None = None
        self.controls = None  # the drag gizmo, on the selected object's top
        self._last_live = 0.0
        self.picked = gui.add_folder("Picked object", visible=False)
        with self.picked:
            self.picked_md = gui.add_markdown("")
            self.pose_x = gui.add_number("x (m)", 0.0, step=0.05)
            self.pose_z = gui.add_number("z (m)", 0.0, step=0.05)
            self.pose_rot = gui.add_number("Rotation (°)", 0.0, step=90)
            gui.add_button("Apply pose").on_click(lambda _: self.apply_pose())
            gui.add_button("Re-place the rest", hint="Keep the objects you moved where you put them and place "
                           "the others again around them").on_click(lambda _: self.replace_rest())
            turns = gui.add_button_group("Turn", ("-90°", "+90°", "Deselect"))
            turns.on_click(lambda e: self.pick(None) if e.target.value == "Deselect"
                           else self.turn(90 if e.target.value == "+90°" else -90))

    def pick(self, object_id: str | None) -> None:
        """Select an object (a click on it): highlighted, its panel above the tabs, the gizmo on its top (in an
        apartment its room becomes the one edited)."""
        s = self.session
        scene = s.displayed()
        if scene is None:
            return
        obj = next((o for o in scene.all_objects() if o.id == object_id), None)
        if obj is not None and s.apartment.current is not None:
            s.apartment.focus_on(obj.id)
        gen = s.state.gen
        self.selected = obj.id if obj is not None else None
        s.view.select(self.selected, scene)
        self.picked.visible = obj is not None
        if obj is None:
            self.place_controls()
            return
        self._show_picked(obj)
        if gen is not None and obj.id in {o.id for o in gen.plan.objects}:
            s.constraints.select(obj.id)
        self.place_controls()

    def _show_picked(self, obj) -> None:
        cat = catalogue()
        t = cat.host(obj.type) if obj.type in cat else None
        flags = ", ".join(k for k, v in (t.flags.items() if t else []) if v) or "—"
        self.picked.label = f"Picked: {obj.id}"
        self.picked_md.content = (f"**{obj.id}** ({obj.type}, {obj.role})\n\nasset `{obj.asset_id}` · "
                                  f"{obj.size.x:.2f} × {obj.size.z:.2f} × {obj.size.y:.2f} m · at ({obj.x:.2f}, "
                                  f"{obj.z:.2f}) facing {obj.rotation:.0f}°\n\n{flags}")
        self.pose_x.value, self.pose_z.value, self.pose_rot.value = round(obj.x, 3), round(obj.z, 3), obj.rotation

    def _offset(self) -> tuple[float, float]:
        """Where the room edited has its (0, 0) corner on screen: the house frame in an apartment."""
        apartment = self.session.apartment
        return apartment.offset() if apartment.current is not None else (0.0, 0.0)

    def _on_screen(self, object_id: str):
        """An object of the room edited as drawn (in the house frame in an apartment)."""
        return next(o for o in self.session.displayed().objects if o.id == object_id)

    def movable(self) -> bool:
        """Is the picked object one of the room edited (which the pose fields and the gizmo move)?"""
        gen = self.session.state.gen
        return gen is not None and self.selected in {o.id for o in gen.plan.objects}

    def place_controls(self) -> None:
        """The drag gizmo sits on the selected object's top and stays there after each drag."""
        if not self.movable():
            if self.controls is not None:
                self.controls.remove()
                self.controls = None
            return
        obj = self._on_screen(self.selected)
        where = world(obj.x, obj.y + obj.size.y / 2 + 0.03, obj.z)
        if self.controls is None:
            self.controls = self.session.client.scene.add_transform_controls(
                "/drag", scale=max(0.5, 0.6 * max(obj.size.x, obj.size.z)), active_axes=(True, False, True),
                disable_rotations=True, depth_test=False, position=where)
            self.controls.on_update(self._dragging)
        else:
            self.controls.position = where
            self.controls.wxyz = (1.0, 0.0, 0.0, 0.0)

    def _dragging(self, event) -> None:
        s = self.session
        if self.selected is None or s.state.gen is None:
            return
        x, _, neg_z = (float(v) for v in self.controls.position)
        dx, dz = self._offset()
        room_x, room_z = x - dx, -neg_z - dz
        rotation = s.state.gen.layout.placement(self.selected).rotation
        if event.phase == "end":
            self.move_to(self.selected, room_x, room_z, rotation, how="drag")
            return
        now = time.perf_counter()  # while dragging: the object follows, the checks re-run (throttled)
        s.view.move(self._on_screen(self.selected).model_copy(update={"x": x, "z": -neg_z}))
        to = s.apartment.room_at(x, -neg_z) if s.apartment.current is not None else None
        if to not in (None, s.state.values.room):
            s.checks_md.content = f"**Release to carry `{self.selected}` into {s.apartment.label(to)}.**"
            return
        if now - self._last_live < LIVE_RESCORE_S:
            return
        self._last_live = now
        s.refresh_checks(s.pipeline.move(s.state.gen, self.selected, room_x, room_z, rotation, s.state.seed))

    def apply_pose(self) -> None:
        if self.movable():
            dx, dz = self._offset()  # the fields show the pose on screen
            self.move_to(self.selected, float(self.pose_x.value) - dx, float(self.pose_z.value) - dz,
                         float(self.pose_rot.value), how="typed pose")

    def turn(self, degrees: int) -> None:
        if self.movable():
            p = self.session.state.gen.layout.placement(self.selected)
            self.move_to(self.selected, p.x, p.z, round((p.rotation + degrees) / 90) * 90, how=f"turn {degrees:+d}°")

    def move_to(self, object_id: str, x: float, z: float, rotation: float, how: str) -> None:
        """A designer's move (drag, typed pose or turn; `x`, `z` in the room's frame): undoable, stored as an
        edit, checked at once."""
        s = self.session
        if s.apartment.current is not None and self._carried(object_id, x, z, rotation, how):
            return
        with s.lock:
            gen = s.state.gen
            before = gen.layout.placement(object_id)
            new = s.pipeline.move(gen, object_id, x, z, rotation, s.state.seed)
            apartment = s.state.values.apartment
            if apartment is not None:
                new, _, apartment = s.apartment.fold(new, None)
            s.history.record(f"move {object_id}", s.state.values)
            put = pose_of(new.layout.placement(object_id))
            moved = tuple(m for m in s.state.values.moved if m[0] != object_id) + ((object_id, put),)
            s.state.values = replace(s.state.values, gen=new, moved=moved, apartment=apartment,
                                     edits=s.state.edits + (move_row(object_id, before, x, z, rotation),))
        obj = self._on_screen(object_id)
        for o in [obj, *obj.children]:
            s.view.move(o)
        self.place_controls()
        if self.selected == object_id:
            self._show_picked(obj)
        findings = s.refresh_checks()
        if apartment is not None:
            s.graph_md.content = s.apartment.summary()  # Key_NAV through the doors after the move
        s.set_unsaved(True)
        s.say(f"Moved `{object_id}` to ({obj.x:.2f}, {obj.z:.2f}) facing {rotation % 360:.0f}° ({how}). "
              + self._checked(findings))

    def _carried(self, object_id: str, x: float, z: float, rotation: float, how: str) -> bool:
        """In an apartment, a move that lands in another room carries the object there (ApartmentMode.carry)."""
        s = self.session
        dx, dz = self._offset()
        to = s.apartment.room_at(x + dx, z + dz)
        if to is None or to == s.state.values.room:
            return False
        new_id = s.apartment.carry(object_id, to, x + dx, z + dz, rotation)
        s.redraw()  # the ids changed
        self.pick(new_id)
        s.constraints.update()
        findings = s.refresh_checks()
        s.graph_md.content = s.apartment.summary()
        s.set_unsaved(True)
        s.say(f"Carried `{object_id}` into {s.apartment.label()} as `{new_id}` ({how}). " + self._checked(findings))
        return True

    def renamed(self, object_id: str) -> str:
        """`object_id` as the scene on screen names it: a carry gives an object a new id, which an undo takes back
        and a redo gives again (the ids of the edit log's `carry` rows)."""
        scene = self.session.displayed()
        if scene is None or any(o.id == object_id for o in scene.all_objects()):
            return object_id
        ids = {o.id for o in scene.objects}
        for e in reversed(self.session.state.edits):
            if e.kind == "carry" and object_id in (e.target, e.after["id"]):
                return next((i for i in (e.target, e.after["id"]) if i in ids), object_id)
        return object_id

    def _checked(self, findings) -> str:
        """The status line's tail after a move: the checks and the edits so far."""
        return ((f"⚠ {len(findings)} check(s) fail." if findings else "All checks pass.")
                + f" {len(self.session.state.edits)} designer edit(s); **Undo** reverts.")

    def still_moved(self) -> list[str]:
        """The objects the designer moved that are still where they were put (a re-plan may have moved them)."""
        s = self.session
        return [oid for oid, pose in s.state.values.moved
                if (p := s.state.gen.layout.placement(oid)) is not None and pose_of(p) == pose]

    def replace_rest(self) -> None:
        """Re-plan from the designer's moves (Pipeline.replace_around): undoable, stored as an edit."""
        s = self.session
        gen = s.state.gen
        if gen is None:
            s.say("**Error:** Nothing to re-place: generate a scene first.")
            return
        moved = self.still_moved()
        if not moved:
            s.say("Move an object first (drag it, type a pose or turn it): **Re-place the rest** keeps the objects "
                  "you moved where you put them and places the others again around them.")
            return
        with s.busy("Re-placing the rest around your moves") as free:
            if not free:
                return
            if not s.run(lambda obs: s.pipeline.replace_around(gen, moved, s.state.seed, s.state.solver, obs),
                         fresh=False, record="re-place the rest", keep_reference=True):
                return
            s.state.values = replace(s.state.values, edits=s.state.edits + (
                Edit("re-place", ", ".join(moved), None, None),))
        shifted = [p.id for p in s.state.gen.layout.placements
                   if (q := gen.layout.placement(p.id)) is None or pose_of(q) != pose_of(p)]
        s.say(f"{s.status.content}\n\nRe-placed around {', '.join(f'`{m}`' for m in moved)} (kept where you put "
              f"them); the placer moved: {', '.join(shifted) or 'nothing'}.")
