"""The studio's apartment mode (room type "apartment"): the whole house on screen, room by room.

The apartment is shown as one Scene in the house frame (every room's objects shifted by the room's
corner), over every room's floor and walls with a label naming the room, with the robot's path through
the doors. The placement steps come from the rooms in floorplan order, so the step animation goes room
by room. A designer edits one room at a time with the single-room tools (constraints, drags, typed poses,
turns, re-placing the rest, undo): a click on an object makes its room the one edited, whose Generation
(room frame) is the session's `gen`; each edit is folded back into the apartment (models.scene.apartment.
with_room), so the robot's path and Key_NAV through the doors follow it. Task-graph corrections regenerate
the whole apartment (the same room types, seed and solver), since the graph decides what goes in which room.
"""

from __future__ import annotations

import contextlib
import threading
import time
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from app.editing import carry_row
from app.pipeline import Generation, pose_of, room_generation
from frontend.captions import parser_note
from frontend.state import Values
from models.checks import Finding, apartment_findings, room_label
from models.language import InstructionError
from models.placement import PlacementStep
from models.planning.apartment_planner import ApartmentError, parse_rooms
from models.planning.floorplan import FloorplanError
from models.scene.apartment import house_objects, with_room
from models.scene.carry import carry
from models.values import Room, Scene, TaskGraph
from models.values.apartment import Apartment

PATH_COLOUR = (200, 40, 160)


def house_scene(apartment: Apartment) -> Scene:
    """The apartment as one Scene in the house frame, its room the house's bounding rectangle."""
    width, depth = apartment.floorplan.size
    return Scene(id=apartment.id, room=Room(type="apartment", width=width, depth=depth),
                 task_graph=apartment.task_graph, objects=house_objects(apartment), unplaced=apartment.unplaced,
                 robot_start=apartment.robot_start, vr_anchor=apartment.vr_anchor, warnings=apartment.warnings)


def first_room(apartment: Apartment) -> int:
    """The room edited first: the anchor's, else the first with objects."""
    ids = [hr.id for hr in apartment.floorplan.rooms]
    if apartment.anchor_room in ids:
        return ids.index(apartment.anchor_room)
    return next((k for k, plan in enumerate(apartment.plans) if plan.objects), 0)


class ApartmentMode:
    def __init__(self, session):
        self.session = session
        self._house: tuple[Apartment, Scene] | None = None  # the house scene of the apartment it was made for

    @property
    def current(self) -> Apartment | None:
        """The apartment on screen (None: a single room is)."""
        return self.session.state.values.apartment

    @property
    def scene(self) -> Scene | None:
        """The apartment on screen as one Scene in the house frame."""
        a = self.current
        if a is None:
            return None
        if self._house is None or self._house[0] is not a:
            self._house = (a, house_scene(a))
        return self._house[1]

    def generate(self) -> None:
        """Generate an apartment from the Task tab (rooms from the Rooms field, or drawn from the task)."""
        s = self.session
        started = time.perf_counter()
        steps: list[PlacementStep] = []
        try:
            rooms = parse_rooms(s.rooms.value) if s.rooms.value.strip() else None
            apartment = s.pipeline.generate_apartment(s.instruction.value, rooms, int(s.seed.value), s.solver.value,
                                                      s.observer(steps))
        except (InstructionError, ApartmentError, FloorplanError) as e:
            s.say(f"**Error:** {e}")
            return
        self.show(apartment, steps, scene_id=None)
        s.set_unsaved(True)
        placed = sum(len(layout.placements) for layout in apartment.layouts)
        s.say(f"Apartment ready (#{s.state.runs}): {len(apartment.scenes)} rooms, {placed} placed, "
              f"{len(apartment.unplaced)} unplaced ({1000 * (time.perf_counter() - started):.0f} ms)."
              + (f"\n\n{parser_note(apartment.task_graph)}" if apartment.task_graph.uncertain else ""))

    def show(self, apartment: Apartment, steps: list[PlacementStep], scene_id: int | None,
             record: str | None = None) -> None:
        """Put an apartment on screen (its steps in the Placement tab); `scene_id`: the stored scene it is;
        `record`: an undoable edit's label (the designer's edits go on), else a new start."""
        s = self.session
        k = first_room(apartment)
        with s.lock:
            if record is None:
                s.history.clear()
                s.state.seed, s.state.solver = int(s.seed.value), s.solver.value
            else:
                s.history.record(record, s.state.values)
            s.state.values = Values(room_generation(apartment, k), tuple(self._in_house(apartment, steps)),
                                    s.state.edits if record else (), apartment=apartment, room=k)
            s.state.shown, s.state.playing, s.state.scene_id = len(steps), False, scene_id
            s.state.runs += 1
            s.picking.selected = None
        s.picking.picked.visible = False
        s.redraw()
        s.set_view("fit" if s.state.view != "top" else "top")
        s.refresh_panels()
        s.refresh_checks()
        threading.Thread(target=self.energy_curve, args=(lambda: self.current is apartment,), daemon=True).start()

    def regenerate(self, graph: TaskGraph) -> None:
        """Regenerate from the Task tab's corrected graph: the same room types in the same order, the same seed and
        solver; undoable."""
        s = self.session
        steps: list[PlacementStep] = []
        rooms = [hr.room.type for hr in self.current.floorplan.rooms]
        try:
            apartment = s.pipeline.generate_apartment_from_graph(graph, rooms, s.state.seed, s.state.solver,
                                                                 s.observer(steps))
        except (ApartmentError, FloorplanError) as e:
            s.say(f"**Error:** {e}\n\nThe apartment on screen is unchanged.")
            return
        self.show(apartment, steps, s.state.scene_id, record="regenerate from graph")
        s.set_unsaved(True)
        s.say(f"Apartment regenerated from the corrected graph (#{s.state.runs}): "
              + ", ".join(f"{o.type} → {apartment.floorplan.room(r).room.type}"
                          for o in graph.objects if (r := apartment.plan.assignment.get(o.type))) + ".")

    def energy_curve(self, current) -> None:
        """The energy plot of the apartment on screen (its rooms summed; each step in its room's frame, as the energy
        is); drawn if `current()` still holds when it is ready."""
        a = self.current
        rooms = [(plan, layout.placements) for plan, layout in zip(a.plans, a.layouts)]
        steps = self._in_house(a, self.session.state.steps, -1)
        self.session.placement.energy_curve(rooms, steps, self.room_of, current)

    def label(self, k: int | None = None) -> str:
        """A room's name on screen, e.g. `room 2 (kitchen)`; the room edited by default."""
        return room_label(self.current, self.session.state.values.room if k is None else k)

    def offset(self) -> tuple[float, float]:
        """Where the room edited has its (0, 0) corner in the house."""
        hr = self.current.floorplan.rooms[self.session.state.values.room]
        return hr.x, hr.z

    def focus_on(self, object_id: str) -> None:
        """Make the room of `object_id` the one edited (a click on one of its objects)."""
        self.focus_room(int(self.room_of(object_id)[1:]) - 1)

    def focus_room(self, k: int) -> None:
        """Make room `k` (from 0) the one edited; not while an edit of the room edited now is being placed, which
        goes back into that room."""
        s = self.session
        if k == s.state.values.room or s.state.busy:
            return
        gen = room_generation(self.current, k, s.state.gen.task_graph)  # the graph's corrections kept
        with s.lock:
            s.state.values = replace(s.state.values, gen=gen, room=k, reference=None)
        s.constraints.update()
        s.refresh_checks()

    def fold(self, gen: Generation, steps: Sequence[PlacementStep] | None) -> tuple[Generation, tuple, Apartment]:
        """An edit of the room edited (`gen`, in its frame, and the placer's `steps` of it, None: no new steps)
        folded back into the apartment: (the room again as the new apartment has it, the house's steps with the
        room's new ones where its old ones were, the new apartment)."""
        s = self.session
        k = s.state.values.room
        apartment = with_room(self.current, k, gen.plan, gen.layout, s.state.seed)
        old = s.state.steps
        room_now = room_generation(apartment, k, gen.task_graph)  # the graph's corrections kept
        if steps is None:
            return room_now, old, apartment
        room = f"r{k + 1}"
        first = next((i for i, step in enumerate(old) if self.room_of(step.object_id) == room), len(old))
        others = [step for step in old if self.room_of(step.object_id) != room]
        spliced = (*others[:first], *self._in_house(apartment, steps), *others[first:])
        return room_now, spliced, apartment

    def room_at(self, x: float, z: float) -> int | None:
        """The room whose floor holds the house-frame point (x, z) (the room edited where two meet; None: no room)."""
        rooms, k = self.current.floorplan.rooms, self.session.state.values.room
        return next((i for i in (k, *range(len(rooms))) if rooms[i].x <= x <= rooms[i].x + rooms[i].room.width
                     and rooms[i].z <= z <= rooms[i].z + rooms[i].room.depth), None)

    def carry(self, object_id: str, to: int, x: float, z: float, rotation: float) -> str:
        """A designer's move that lands (house frame) in room `to`: the object and what stands on it go there
        (models.scene.carry), that room becomes the one edited, and its placer steps leave the animation; undoable,
        stored as a `carry` edit. Returns the object's new id."""
        s = self.session
        k, before = s.state.values.room, s.state.gen.layout.placement(object_id)
        hr = self.current.floorplan.rooms[to]
        with s.lock:
            apartment, new_id = carry(self.current, object_id, to, x - hr.x, z - hr.z, rotation, s.state.seed)
            s.history.record(f"carry {object_id}", s.state.values)
            put = apartment.layouts[to].placement(new_id)
            edit = carry_row(object_id, k + 1, before, new_id, to + 1, put)
            steps = tuple(step for step in s.state.steps if step.object_id != object_id)
            shown = len(steps) if s.state.shown >= len(s.state.steps) else min(s.state.shown, len(steps))
            moved = tuple(m for m in s.state.values.moved if m[0] != object_id) + ((new_id, pose_of(put)),)
            s.state.values = replace(s.state.values, gen=room_generation(apartment, to, s.state.gen.task_graph),
                                     steps=steps, edits=s.state.edits + (edit,), moved=moved, reference=None,
                                     apartment=apartment, room=to)
            s.state.shown = shown
        threading.Thread(target=self.energy_curve, args=(lambda: self.current is apartment,), daemon=True).start()
        return new_id

    def findings(self) -> list[Finding]:
        return apartment_findings(self.current)

    def save(self, overridden: list[Finding]) -> None:
        """Store the apartment as a new scene, or as the next version of the stored apartment on screen, with the
        designer's edits and the checks saved over (the Scenes tab asks first)."""
        s, a = self.session, self.current
        name = s.scenes.save_name.value.strip() or a.task_graph.instruction[:60]
        sid, number = s.scenes.store_version(name, a, s.scenes.edits_with(overridden))
        s.state.values = replace(s.state.values, edits=())
        s.say(f"Saved as scene {sid}, version {number} (“{name}”): an apartment of {len(a.scenes)} rooms"
              + (f", overriding {len(overridden)} failed check(s)." if overridden else "."))

    def open(self, apartment: Apartment, scene_id: int, number: int, stored: dict) -> None:
        """Show a stored apartment; the Placement tab replays each room's placer with the stored solver and the
        seed its layout kept (a room the robot crosses may have been placed again with the next seed; the stored
        poses stay what is shown)."""
        s = self.session
        steps: list[PlacementStep] = []
        with contextlib.suppress(Exception):  # a solver that no longer exists: the apartment opens without replay
            for plan, layout in zip(apartment.plans, apartment.layouts):
                s.pipeline.place(plan, layout.seed, s.solver.value, s.observer(steps))
        self.show(apartment, steps, scene_id=scene_id)
        s.set_unsaved(False)
        s.instruction.value = apartment.task_graph.instruction
        s.say(f"Opened scene {scene_id}, version {number}: an apartment of {len(apartment.scenes)} rooms "
              f"(seed {stored['seed']}, solver `{stored['solver']}`).")

    @staticmethod
    def room_of(object_id: str) -> str:
        """The room an apartment's object is placed in: its id's prefix (`r2-chair-0` -> `r2`)."""
        return object_id.split("-", 1)[0]

    def _in_house(self, apartment: Apartment, steps: Sequence[PlacementStep], sign: int = 1) -> list[PlacementStep]:
        """Each step's pose and candidates moved from its room's frame to the house frame (for the animation and the
        heat-map); `sign` -1: back to the room's frame."""
        offsets = {hr.id.split("|")[1]: (sign * hr.x, sign * hr.z) for hr in apartment.floorplan.rooms}
        out = []
        for step in steps:
            x, z = offsets[self.room_of(step.object_id)[1:]]
            moved = step.candidates + np.array([x, z, 0.0]) if len(step.candidates) else step.candidates
            out.append(replace(step, candidates=moved, x=None if step.x is None else step.x + x,
                               z=None if step.z is None else step.z + z))
        return out

    def where(self, step: PlacementStep) -> str:
        """The step's room, e.g. `room 2 / 4 (kitchen): `."""
        rooms = self.current.floorplan.rooms
        k = int(self.room_of(step.object_id)[1:])
        return f"room {k} / {len(rooms)} ({rooms[k - 1].room.type}): "

    def summary(self) -> str:
        a = self.current
        rooms = "; ".join(f"{hr.id.split('|')[1]}. {hr.room.type} ({hr.room.width:.1f} × {hr.room.depth:.1f} m)"
                          for hr in a.floorplan.rooms)
        objects = ", ".join(f"{t} → {a.floorplan.room(r).room.type}" for t, r in a.plan.assignment.items())
        nav = "n/a" if a.key_nav is None else f"{100 * a.key_nav:.0f} %"
        return (f"**Apartment:** {rooms}\n\n**Task objects:** {objects}\n\n**Key_NAV through the doors:** {nav} "
                f"(E_nav {a.e_nav:.2f})" + (f"; unreachable: {', '.join(a.path.unreachable)}" if a.path.unreachable
                                           else ""))

    def draw(self, house: Scene, visible: set[str] | None, labels: bool) -> None:
        """The house: each room's shell and label, the markers, the objects of `house` (as the step animation shows
        it now; `visible`: the ids on show, None: all), the robot's path and the step's heat-map."""
        s, a = self.session, self.current
        with s.client.atomic():
            s.view.clear()
            for hr in a.floorplan.rooms:
                s.view.draw_shell(hr.room, hr.x, hr.z, f"/room/{hr.id.split('|')[1]}")
                s.view.room_label(f"{hr.id.split('|')[1]}. {hr.room.type}", hr.x + hr.room.width / 2,
                                  hr.z + hr.room.depth / 2)
            s.view.draw_markers(self.scene)
            s.view.draw_objects(house, visible, labels)
            s.view.draw_path(a.path.points, PATH_COLOUR)
            shown, steps = s.state.shown, s.state.steps
            step = steps[shown - 1] if 0 < shown <= len(steps) else None
            s.view.heat_map(step if s.placement.heat.value and shown < len(steps) else None)
