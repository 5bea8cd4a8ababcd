"""One designer's session in one browser tab: its own GUI handles, 3D view and state (viser per-client).

Above the tabs: the status and progress lines, the view buttons (fit, top, VR user's view), undo / redo,
the live checks and the picked object's panel (pose fields, 90 degree turns), so they show on every tab.
Tabs: Task (instruction, room type, seed, solver, Generate; the task graph, corrected in frontend.graph_panel) is
here; Placement (frontend.placement_panel), Constraints (frontend.constraints_panel), Scenes (frontend.scenes_panel)
and Headset (frontend.headset_panel) are panels of their own that act through the session's shared steps (`run`,
`busy`, `confirm`, `say`).
"""

from __future__ import annotations

import contextlib
import logging
import threading
import time
from dataclasses import replace

import numpy as np
import viser
from viser import _messages

from app.pipeline import Generation, Pipeline
from frontend import camera
from frontend.apartment import ApartmentMode
from frontend.captions import (exact_note, graph_summary, metrics_table, parser_note, placing_progress,
                               unplaced_note)
from frontend.checks import summary
from frontend.constraints_panel import ConstraintsPanel
from frontend.graph_image import render as render_graph
from frontend.graph_panel import GraphPanel
from frontend.history import History
from frontend.picking_panel import PickingPanel
from frontend.placement_panel import PlacementPanel
from frontend.replay import RoomOf, one_room, room_at
from frontend.scenes_panel import ScenesPanel
from frontend.state import State, Values
from frontend.view import SceneView, world
from models.checks import Finding, run_checks
from models.energy.exact import layout_energy
from models.language import InstructionError
from models.metrics.realism import checks as habit_checks
from models.placement import ALL_OBJECTS, DEFAULT_SOLVER, EXACT_FINISH, SOLVERS, PlacementStep
from models.values import Scene, TaskGraph
from models.values.apartment import APARTMENT
from models.values.edit import Edit
from models.world import INFER, ROOM_TYPES
from studio_db import Store

DEFAULT_INSTRUCTION = "Put a chilled bread on the counter"
PROGRESS_S = 0.2  # the progress line is updated at most this often while placing
UNSAVED_JS = """
if (!window.__h3dsUnsavedHook) {
  window.__h3dsUnsavedHook = true;
  window.addEventListener('beforeunload', (e) => {
    if (window.__h3dsUnsaved) { e.preventDefault(); e.returnValue = ''; }
  });
}
"""


class StudioSession:
    def __init__(self, client: viser.ClientHandle, pipeline: Pipeline, store: Store):
        self.client, self.pipeline, self.store = client, pipeline, store
        self.state = State()
        self.history = History()
        self.lock = threading.RLock()
        self.view = SceneView(client.scene)
        self.view.on_pick = lambda object_id: self.picking.pick(object_id)
        self.apartment = ApartmentMode(self)
        self.closed = False  # the tab has gone: nothing more is drawn
        self._run_js(camera.ORBIT_LIMIT_JS + UNSAVED_JS)
        self._build_gui()
        self._run_js(camera.CANVAS_SIZE_JS.replace("UUID", self.canvas_size._impl.uuid))

    def close(self) -> None:
        """The tab closed: stop the step animation, whose thread would otherwise draw into a closed connection."""
        self.closed = True
        self.state.playing = False

    # ---- GUI --------------------------------------------------------------------------------------

    def _build_gui(self) -> None:
        gui = self.client.gui
        gui.configure_theme(control_width="large")
        self.canvas_size = gui.add_vector2("Canvas (CSS px)", (0.0, 0.0), visible=False)  # reported by the page
        self.canvas_size.on_update(lambda _: self._canvas_resized())
        self.status = gui.add_markdown("Type an instruction and press **Generate**.")
        self.progress = gui.add_markdown("")
        views = gui.add_button_group("View", ("Fit room", "Top view", "VR user's view"))
        views.on_click(lambda e: self.set_view({"Fit room": "room", "Top view": "top",
                                                "VR user's view": "vr"}[e.target.value]))
        edits = gui.add_button_group("Edits", ("Undo", "Redo"))
        edits.on_click(lambda e: self.undo() if e.target.value == "Undo" else self.redo())
        self.checks_md = gui.add_markdown("")
        self.picking = PickingPanel(self, gui)
        tabs = gui.add_tab_group()

        with tabs.add_tab("Task"):
            self.instruction = gui.add_text("Instruction", DEFAULT_INSTRUCTION)
            self.room = gui.add_dropdown("Room type", (INFER,) + ROOM_TYPES + (APARTMENT,), initial_value="kitchen")
            self.rooms = gui.add_text("Rooms (apartment)", "", hint="e.g. kitchen, living room, bedroom; empty: "
                                      "2-5 rooms drawn from the task")
            self.seed = gui.add_number("Seed", 0, min=0, step=1)
            self.solver = gui.add_dropdown("Solver", tuple(sorted(SOLVERS)), initial_value=DEFAULT_SOLVER,
                                           hint=f"{DEFAULT_SOLVER} may leave out an object that would cut a task "
                                           f"object off from the robot; {ALL_OBJECTS} places every object it can; "
                                           f"{EXACT_FINISH} asks Z3 over a small room even where most constraints "
                                           "are broken")
            self.generate_button = gui.add_button("Generate", color="green")
            self.generate_button.on_click(lambda _: self.generate())
            self.graph_md = gui.add_markdown("")
            self.graph_img = gui.add_image(np.full((300, 480, 3), 255, np.uint8), label="Task scene graph",
                                           visible=False)
            with gui.add_folder("Correct the task graph", expand_by_default=False):
                self.graph = GraphPanel(self, gui)

        with tabs.add_tab("Placement"):
            self.placement = PlacementPanel(self, gui)

        with tabs.add_tab("Constraints"):
            self.constraints = ConstraintsPanel(self, gui)

        with tabs.add_tab("Scenes"):
            self.scenes = ScenesPanel(self, gui)

        with tabs.add_tab("Headset"):
            from frontend.headset_panel import HeadsetPanel
            self.headset_panel = HeadsetPanel(self, gui)
        self.scenes.list_scenes()

    def say(self, text: str) -> None:
        self.status.content = text

    def _run_js(self, source: str) -> None:
        """Run a snippet in this tab (viser's own message for it; there is no public method)."""
        self.client._websock_connection.queue_message(_messages.RunJavascriptMessage(source=source))

    def set_unsaved(self, unsaved: bool) -> None:
        """Track unsaved work; while there is some, leaving or reloading the page asks first."""
        if unsaved != self.state.unsaved:
            self.state.unsaved = unsaved
            self._run_js(f"window.__h3dsUnsaved = {'true' if unsaved else 'false'};")

    def confirm(self, title: str, text: str, yes: str, action) -> None:
        """A modal asking the designer to confirm; `action` runs only on `yes`."""
        gui = self.client.gui
        with gui.add_modal(title) as modal:
            gui.add_markdown(text)
            gui.add_button(yes, color="red").on_click(lambda _: (modal.close(), action()))
            gui.add_button("Cancel").on_click(lambda _: modal.close())

    # ---- busy state -------------------------------------------------------------------------------

    @contextlib.contextmanager
    def busy(self, what: str):
        """Generate and Regenerate are disabled while a pipeline step runs; a second click is ignored."""
        with self.lock:
            if self.state.busy:
                yield False
                return
            self.state.busy = True
        self.generate_button.disabled = self.graph.regenerate_button.disabled = True
        self.progress.content = f"⏳ {what}…"
        try:
            yield True
        finally:
            self.generate_button.disabled = self.graph.regenerate_button.disabled = False
            self.progress.content = ""
            self.state.busy = False

    def observer(self, steps: list[PlacementStep]):
        last = [0.0]

        def observe(step: PlacementStep) -> None:
            steps.append(step)
            now = time.perf_counter()
            if now - last[0] > PROGRESS_S:
                last[0] = now
                self.progress.content = placing_progress(steps)
        return observe

    # ---- generating -------------------------------------------------------------------------------

    def generate(self) -> None:
        with self.busy("Reading the instruction") as free:
            if not free:
                return
            if self.room.value == APARTMENT:
                self.progress.content = "⏳ Planning the rooms, the floorplan and placing objects…"
                self.apartment.generate()
                return
            try:
                graph = self.pipeline.parse(self.instruction.value, self.room.value)
            except (InstructionError, ValueError) as e:
                self._clear_graph()
                self.say(f"**Error:** {e}\n\nInstructions are read in English, one task at a time. The task graph "
                         "was cleared; the 3D scene is still the previous one.")
                return
            self.progress.content = "⏳ Planning the room and placing objects…"
            seed, solver = int(self.seed.value), self.solver.value
            self.run(lambda observer: self.pipeline.generate_from_graph(graph, seed, solver, observer),
                      fresh=True, note=parser_note(graph))

    def _clear_graph(self) -> None:
        self.graph_md.content = ""
        self.graph_img.visible = False

    def run(self, make, fresh: bool, note: str = "", record: str | None = None, keep_reference: bool = False) -> bool:
        """Run a pipeline step with an observer collecting placement steps, then show the result.

        `fresh`: a new scene (no edits, not stored, camera framed); `record`: an undoable edit's label;
        `keep_reference`: the checks compare with the metrics from before (a constraint edit)."""
        started = time.perf_counter()
        steps: list[PlacementStep] = []
        try:
            gen = make(self.observer(steps))
        except Exception as e:  # shown to the designer; the stored scenes and the current one are untouched
            logging.getLogger(__name__).exception("pipeline step failed")
            self.say(f"**Error:** {type(e).__name__}: {e}")
            return False
        with self.lock:
            if record is not None:
                self.history.record(record, self.state.values)
            self.state.playing = False
            before = self.state.values
            apartment = None if fresh else before.apartment
            if apartment is not None:  # an edit of one room of the apartment on screen
                gen, steps, apartment = self.apartment.fold(gen, steps)
            edits, moved = ((), ()) if fresh else (before.edits, before.moved)
            reference = before.reference if keep_reference else None
            self.state.values = Values(gen, tuple(steps), edits, reference, moved, apartment,
                                       None if apartment is None else before.room)
            if fresh:
                self.state.seed, self.state.solver = int(self.seed.value), self.solver.value
                self.state.scene_id = None
                self.history.clear()
            self.state.shown = len(steps)
            self.state.runs += 1
        self.redraw(labels=False)
        if self.picking.selected is not None:
            self.picking.pick(self.picking.selected)  # its panel shows the new scene's object, or closes if it is gone
        if fresh:
            self.set_view("fit" if self.state.view != "top" else "top")
        self.refresh_panels()
        self.set_unsaved(True)
        placed = len(gen.layout.placements)
        where = (f"the apartment's {self.apartment.label()}" if self.apartment.current
                 else f"**{gen.task_graph.room_type}**")
        self.say(f"Scene ready (#{self.state.runs}): {placed} placed, {len(gen.layout.unplaced)} unplaced "
                 f"({1000 * (time.perf_counter() - started):.0f} ms). Room: {where}."
                 + "".join(f"\n\n{n}" for n in (unplaced_note(gen.layout.unplaced), note) if n))
        self.checks_md.content = "**Checks:** running…"
        threading.Thread(target=self._after_scene, args=(gen, steps), daemon=True).start()
        return True

    def _after_scene(self, gen: Generation, steps: list[PlacementStep]) -> None:
        """The slower read-outs (checks, metrics, per-step energies) follow the scene instead of delaying
        it; saving runs the checks again, so nothing is saved unchecked."""
        with self.lock:
            if self.state.gen is gen:
                self.refresh_checks()
            if self.state.gen is gen and not self.view.labels:
                self.view.draw_labels(self.displayed(), self._visible())
        if self.apartment.current is not None:
            self.apartment.energy_curve(lambda: self.state.gen is gen)
        else:
            self.placement.energy_curve([(gen.plan, gen.layout.placements)], steps, one_room,
                                        lambda: self.state.gen is gen)

    def redraw(self, labels: bool = True) -> None:
        if self.apartment.current is not None:
            self.apartment.draw(*self._shown(), labels)
            return
        gen = self.state.gen
        if gen is None:
            return
        with self.client.atomic():
            self.view.clear()
            self.view.draw_room(gen.scene)
            self.view.draw_objects(*self._shown(), labels)
            shown, steps = self.state.shown, self.state.steps
            step = steps[shown - 1] if 0 < shown <= len(steps) else None
            self.view.heat_map(step if self.placement.heat.value and shown < len(steps) else None)
        self.picking.place_controls()

    def room_of(self) -> RoomOf:
        """Which room an object is placed in: an apartment's rooms are solved one by one."""
        return self.apartment.room_of if self.apartment.current is not None else one_room

    def _shown(self) -> tuple[Scene | None, set[str] | None]:
        """The scene as the step animation shows it now (frontend.replay) and the ids on show (None: all)."""
        scene = self.displayed()
        if scene is None:
            return None, None
        return room_at(scene, self.state.steps, self.state.shown, self.room_of())

    def _visible(self) -> set[str] | None:
        """The ids on show in the step animation (None: all of them)."""
        return self._shown()[1]

    def displayed(self) -> Scene | None:
        """The scene on screen: the generated room, or the whole apartment in the house frame."""
        if self.apartment.current is not None:
            return self.apartment.scene
        return self.state.gen.scene if self.state.gen is not None else None

    # ---- the camera -------------------------------------------------------------------------------

    def set_view(self, mode: str) -> None:
        """Frame the scene beside the panel ("fit": the room, or the whole apartment), frame the room ("room": in an
        apartment, the one edited), look straight down on the scene ("top", near-orthographic) or stand where the
        VR user stands ("vr")."""
        scene, cam, canvas = self.displayed(), self.client.camera, self.canvas()
        if scene is None or canvas is None:
            return
        width, height = canvas
        room = scene.room
        if mode == "vr" and scene.vr_anchor is not None:
            v = scene.vr_anchor
            position, look_at = camera.vr_view(v.x, v.z, v.rotation)
            fov = camera.VR_FOV
        elif mode == "top":
            fov = camera.TOP_FOV
            position, look_at = camera.fit(camera.room_points(room.width, room.depth, 0.0), (0.0, -1.0, -1e-4),
                                           fov, width, height)
        else:
            fov = camera.DEFAULT_FOV
            direction = camera.framing_direction(cam.position, cam.look_at) if mode in ("fit", "room") and \
                self.state.runs > 1 else camera.DEFAULT_DIRECTION
            points = camera.room_points(room.width, room.depth)
            if mode == "room" and self.apartment.current is not None:  # the room edited, where it is in the house
                hr = self.apartment.current.floorplan.rooms[self.state.values.room]
                points = camera.room_points(hr.room.width, hr.room.depth) + world(hr.x, 0.0, hr.z)
            position, look_at = camera.fit(points, direction, fov, width, height)
        with self.client.atomic():
            self.view.set_top_view(mode == "top")
            cam.fov = fov
            cam.position = position  # position first: viser moves look-at along with a new position
            cam.look_at = look_at
        self.state.view, self.state.canvas = mode, (width, height)  # last: a reader sees the camera already moved

    def canvas(self) -> tuple[int, int] | None:
        """The canvas's size in CSS pixels, as the page reports it (camera.CANVAS_SIZE_JS); until it has, the size of
        the camera's drawing buffer (the same where the device pixel ratio is 1); None before either."""
        width, height = self.canvas_size.value
        if width > 0 and height > 0:
            return int(width), int(height)
        try:
            return self.client.camera.image_width, self.client.camera.image_height
        except AssertionError:  # the browser has not reported its camera yet
            return None

    def _canvas_resized(self) -> None:
        """Refit after the window is resized (the canvas's CSS size changed), keeping the current kind of view; a
        change of the drawing buffer alone (viser's adaptive resolution) moves nothing."""
        if self.displayed() is not None and self.state.canvas != (0, 0) and self.canvas() != self.state.canvas:
            self.set_view(self.state.view)

    # ---- panels -----------------------------------------------------------------------------------

    def refresh_panels(self) -> None:
        g = self.state.gen.task_graph
        self.graph_md.content = self.apartment.summary() if self.apartment.current else graph_summary(g)
        threading.Thread(target=self.draw_graph, args=(g,), daemon=True).start()
        self.graph.update()
        self.constraints.update()

    def draw_graph(self, graph: TaskGraph) -> None:
        self.graph_img.image = render_graph(graph)
        self.graph_img.visible = True

    def refresh_checks(self, gen: Generation | None = None) -> list[Finding]:
        """Run the checks on the scene (or on a drag in progress) and show them with the metrics."""
        gen = gen or self.state.gen
        findings, m = run_checks(gen.plan, gen.layout, gen.scene, self.state.values.reference)
        if self.state.values.reference is None and gen is self.state.gen:
            self.state.values = replace(self.state.values, reference=m)
        if gen is self.state.gen:
            self.state.findings = findings
        where = f"*In {self.apartment.label()}:* " if self.apartment.current is not None else ""
        self.checks_md.content = where + summary(findings)
        energy = layout_energy(gen.plan, gen.layout.placements).total
        self.constraints.metrics.content = metrics_table(m, energy, habit_checks(gen.plan, gen.layout)) + \
            exact_note(m, gen.plan, self.state.solver)
        return findings

    # ---- undo / redo ------------------------------------------------------------------------------

    def undo(self) -> None:
        self._restore(self.history.undo(self.state.values), "Undid")

    def redo(self) -> None:
        self._restore(self.history.redo(self.state.values), "Redid")

    def _restore(self, snap, verb: str) -> None:
        if snap is None:
            self.say("Nothing to undo." if verb == "Undid" else "Nothing to redo.")
            return
        with self.lock:  # the edit log keeps what was done and says it was undone (or redone)
            log = Edit("undo" if verb == "Undid" else "redo", snap.label, None, None)
            self.state.values = replace(snap.values, edits=self.state.edits + (log,))
            self.state.shown = len(self.state.steps)
        self.redraw()
        self.refresh_panels()
        self.refresh_checks()
        if self.picking.selected:
            self.picking.pick(self.picking.renamed(self.picking.selected))
        self.set_unsaved(True)
        self.say(f"{verb}: {snap.label}.")
