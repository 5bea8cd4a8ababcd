"""One designer's session in one browser tab: its own GUI handles, 3D view and state (viser per-client).

Panels: Task (instruction, room type, seed, solver, Generate; the task graph with role corrections),
Placement (play / pause / step / speed, heat-map, energy plot), Constraints (per-object list with
dropdowns, raw text, metrics, the picked object's properties), Scenes (accept & save, stored scenes
and versions, downloads) and Headset (reserved for the headset bridge).
"""

from __future__ import annotations

import contextlib
import json
import logging
import threading
import time
from dataclasses import dataclass, field

import numpy as np
import viser

from app.pipeline import Generation, Pipeline, generation_of, kept_before_edit
from frontend.graph_image import render as render_graph
from frontend.view import SceneView, rotation_of, world
from models.constraints import GLOBALS, RELATIONS, Constraint, read_constraints, write_constraints
from models.energy.exact import layout_energy
from models.exports.glb import ROLE_COLOURS, to_glb
from models.exports.procthor_house import to_house
from models.language import InstructionError
from models.metrics import scene_metrics
from models.placement import SOLVERS, PlacementStep
from models.values import TaskGraph, TaskObject
from models.world import ROOM_TYPES, catalogue
from studio_db import Store
from studio_db.store import Edit

ROLE_MARK = {role: f'<span style="color:rgb{tuple(ROLE_COLOURS[role][:3])}">&#9632;</span>'
             for role in ("key", "anchor", "inference")}
ROLE_CHOICES = ("key", "anchor", "inference", "key + anchor", "anchor + inference")
ENERGY_TERMS = ("rel", "collision", "oob", "nav", "aff", "total")
DEFAULT_INSTRUCTION = "Put a chilled bread on the counter"
LIVE_RESCORE_S = 0.3


@dataclass
class State:
    gen: Generation | None = None
    steps: list[PlacementStep] = field(default_factory=list)
    shown: int = 0  # objects shown so far in the step animation
    playing: bool = False
    edits: list[Edit] = field(default_factory=list)
    scene_id: int | None = None
    seed: int = 0
    solver: str = "dfs"
    runs: int = 0  # scenes shown in this tab so far (numbers the status line)


class StudioSession:
    def __init__(self, client: viser.ClientHandle, pipeline: Pipeline, store: Store):
        self.client, self.pipeline, self.store = client, pipeline, store
        self.state = State()
        self.lock = threading.RLock()
        self.view = SceneView(client.scene)
        self.view.on_pick = self.pick
        self.controls = None
        self._last_live = 0.0
        self._build_gui()

    # ---- GUI --------------------------------------------------------------------------------------

    def _build_gui(self) -> None:
        gui = self.client.gui
        gui.configure_theme(control_width="large")
        self.status = gui.add_markdown("Type an instruction and press **Generate**.")
        tabs = gui.add_tab_group()

        with tabs.add_tab("Task"):
            self.instruction = gui.add_text("Instruction", DEFAULT_INSTRUCTION)
            self.room = gui.add_dropdown("Room type", ("infer",) + ROOM_TYPES, initial_value="kitchen")
            self.seed = gui.add_number("Seed", 0, min=0, step=1)
            self.solver = gui.add_dropdown("Solver", tuple(sorted(SOLVERS)), initial_value="dfs")
            gui.add_button("Generate", color="green").on_click(lambda _: self.generate())
            self.graph_md = gui.add_markdown("")
            self.graph_img = gui.add_image(np.full((300, 480, 3), 255, np.uint8), label="Task scene graph",
                                           visible=False)
            with gui.add_folder("Correct the task graph", expand_by_default=False):
                self.role_object = gui.add_dropdown("Object", ("-",))
                self.role_choice = gui.add_dropdown("Role", ROLE_CHOICES)
                gui.add_button("Set role").on_click(lambda _: self.set_role())
                self.new_object = gui.add_text("Add object type", "")
                gui.add_button("Add object").on_click(lambda _: self.add_object())
                gui.add_button("Remove object").on_click(lambda _: self.remove_object())
                gui.add_button("Regenerate from graph").on_click(lambda _: self.regenerate())

        with tabs.add_tab("Placement"):
            buttons = gui.add_button_group("Animation", ("Play", "Pause", "Step", "Show all"))
            buttons.on_click(lambda e: self.animate(e.target.value))
            self.speed = gui.add_slider("Objects / s", 0.5, 10.0, 0.5, 3.0)
            self.step_md = gui.add_markdown("")
            self.heat = gui.add_checkbox("Candidate heat-map", True)
            self.energy_plot = gui.add_uplot(
                data=(np.zeros(1), *[np.zeros(1) for _ in ENERGY_TERMS]),
                series=({"label": "step"}, *[{"label": t, "stroke": c} for t, c in
                                              zip(ENERGY_TERMS, ("#e07b39", "#c0392b", "#8e44ad", "#2980b9",
                                                                 "#27ae60", "#111111"))]),
                title="Energy terms per step", aspect=1.6, scales={"x": {"time": False}})

        with tabs.add_tab("Constraints"):
            self.c_object = gui.add_dropdown("Object", ("-",))
            self.c_object.on_update(lambda _: self.show_constraints())
            self.c_list = gui.add_markdown("")
            self.c_type = gui.add_dropdown("Constraint", GLOBALS + RELATIONS, initial_value="near")
            self.c_target = gui.add_dropdown("Target", ("-",))
            gui.add_button("Add constraint").on_click(lambda _: self.add_constraint())
            gui.add_button("Remove its relations").on_click(lambda _: self.clear_relations())
            self.c_text = gui.add_text("Raw constraints", "", multiline=True)
            gui.add_button("Apply text").on_click(lambda _: self.apply_text(self.c_text.value))
            self.c_message = gui.add_markdown("")
            self.metrics_md = gui.add_markdown("")
            self.picked_md = gui.add_markdown("")

        with tabs.add_tab("Scenes"):
            self.save_name = gui.add_text("Name", "")
            gui.add_button("Accept & save", color="blue").on_click(lambda _: self.accept())
            self.stored = gui.add_dropdown("Stored scene", ("-",))
            self.stored.on_update(lambda _: self.list_versions())
            self.version = gui.add_dropdown("Version", ("-",))
            gui.add_button("Open").on_click(lambda _: self.open_version())
            gui.add_button("Refresh list").on_click(lambda _: self.list_scenes())
            gui.add_button("Download house JSON").on_click(lambda _: self.download("house"))
            gui.add_button("Download GLB").on_click(lambda _: self.download("glb"))

        with tabs.add_tab("Headset"):
            gui.add_button("Send to headset", disabled=True, hint="arrives with the headset bridge")
            gui.add_markdown("Live glove feedback will stream here once the headset bridge lands.")
        self.list_scenes()

    def say(self, text: str) -> None:
        self.status.content = text

    # ---- generating -------------------------------------------------------------------------------

    def generate(self) -> None:
        room = None if self.room.value == "infer" else self.room.value
        try:
            graph = self.pipeline.parse(self.instruction.value, room)
        except (InstructionError, ValueError) as e:
            self.say(f"**Error:** {e}")
            return
        self._run(lambda observer: self.pipeline.generate_from_graph(graph, int(self.seed.value), self.solver.value,
                                                                     observer), fresh=True)

    def _run(self, make, fresh: bool) -> None:
        """Run a pipeline step with an observer collecting placement steps, then show the result."""
        started = time.perf_counter()
        steps: list[PlacementStep] = []
        try:
            gen = make(steps.append)
        except Exception as e:  # shown to the designer; the stored scenes and the current one are untouched
            logging.getLogger(__name__).exception("pipeline step failed")
            self.say(f"**Error:** {type(e).__name__}: {e}")
            return
        with self.lock:
            self.state.playing = False
            self.state.gen, self.state.steps = gen, steps
            self.state.seed, self.state.solver = int(self.seed.value), self.solver.value
            if fresh:
                self.state.edits, self.state.scene_id = [], None
            self.state.shown = len(steps)
            self.state.runs += 1
        self.redraw()
        if fresh:
            self.look_at_room()
        self.refresh_panels()
        placed = len(gen.layout.placements)
        self.say(f"Scene ready (#{self.state.runs}): {placed} placed, {len(gen.layout.unplaced)} unplaced "
                 f"({1000 * (time.perf_counter() - started):.0f} ms). Room: **{gen.task_graph.room_type}**.")
        threading.Thread(target=self._after_scene, args=(gen, steps), daemon=True).start()

    def _after_scene(self, gen: Generation, steps: list[PlacementStep]) -> None:
        """The slower read-outs (metrics, per-step energies) follow the scene instead of delaying it."""
        self.show_metrics()
        self._energy_curve(gen, steps)

    def look_at_room(self) -> None:
        room = self.state.gen.scene.room
        size = max(room.width, room.depth)
        self.client.camera.look_at = world(room.width / 2, 0.0, room.depth / 2)
        self.client.camera.position = world(room.width / 2, 1.3 * size, -0.55 * size)

    def redraw(self) -> None:
        gen = self.state.gen
        if gen is None:
            return
        with self.client.atomic():
            self.view.clear()
            self.view.draw_room(gen.scene)
            visible = self._visible()
            self.view.draw_objects(gen.scene, visible)
            step = self.state.steps[self.state.shown - 1] if 0 < self.state.shown <= len(self.state.steps) else None
            self.view.heat_map(step if self.heat.value and self.state.shown < len(self.state.steps) else None)
        self.controls = None

    def _visible(self) -> set[str] | None:
        if self.state.shown >= len(self.state.steps):
            return None
        placed_ids = {s.object_id for s in self.state.steps[:self.state.shown]}
        scene = self.state.gen.scene
        return placed_ids | {c.id for o in scene.objects if o.id in placed_ids for c in o.children}

    # ---- the step animation -----------------------------------------------------------------------

    def animate(self, command: str) -> None:
        if self.state.gen is None:
            return
        if command == "Play":
            if self.state.shown >= len(self.state.steps):
                self.state.shown = 0
                self.redraw()
            self.state.playing = True
            threading.Thread(target=self._play, daemon=True).start()
        elif command == "Pause":
            self.state.playing = False
        elif command == "Step":
            self.state.playing = False
            if self.state.shown >= len(self.state.steps):
                self.state.shown = 0
                self.redraw()
            self._advance()
        elif command == "Show all":
            self.state.playing = False
            self.state.shown = len(self.state.steps)
            self.redraw()
            self.step_md.content = "All objects shown."

    def _play(self) -> None:
        while self.state.playing and self.state.shown < len(self.state.steps):
            self._advance()
            time.sleep(max(0.0, 1.0 / float(self.speed.value) - 0.25))
        self.state.playing = False

    def _advance(self) -> None:
        """Show the next step: heat-map of its candidates, then the object settling into place."""
        with self.lock:
            steps = self.state.steps
            if self.state.shown >= len(steps):
                return
            step = steps[self.state.shown]
            self.state.shown += 1
        if self.heat.value:
            self.view.heat_map(step)
        where = "no valid position (unplaced)" if step.x is None else \
            f"x {step.x:.2f} m, z {step.z:.2f} m, facing {step.rotation:.0f}°"
        self.step_md.content = f"**Step {self.state.shown} / {len(steps)}**: placing `{step.object_id}` at {where}"
        if step.x is None:
            return
        frames = max(2, min(8, int(20 / float(self.speed.value))))  # fewer frames when playing fast
        duration = min(0.25, 0.8 / float(self.speed.value))
        for k in range(1, frames + 1):
            self.view.drop_in(step.object_id, self.state.gen.scene, k / frames)
            for child in next((o.children for o in self.state.gen.scene.objects if o.id == step.object_id), []):
                self.view.drop_in(child.id, self.state.gen.scene, k / frames)
            time.sleep(duration / frames)
        if self.state.shown == len(steps):
            self.view.heat_map(None)

    def _energy_curve(self, gen: Generation, steps: list[PlacementStep]) -> None:
        """The paper's energy terms after each placement step (exact energy), drawn when ready."""
        placed, rows = [], []
        by_id = {p.id: p for p in gen.layout.placements}
        for step in steps:
            if step.object_id in by_id:
                placed.append(by_id[step.object_id])
            rows.append(layout_energy(gen.plan, placed).as_dict())
        if self.state.gen is not gen or not rows:
            return
        xs = np.arange(1, len(rows) + 1, dtype=float)
        self.energy_plot.data = (xs, *[np.array([r[t] for r in rows]) for t in ENERGY_TERMS])

    # ---- panels -----------------------------------------------------------------------------------

    def refresh_panels(self) -> None:
        gen = self.state.gen
        g = gen.task_graph
        lines = [f"**Room:** {g.room_type} · **task:** `{g.task_type}`", ""]
        for role, title in (("key", "Key objects"), ("anchor", "Anchor object"), ("inference", "Inference objects")):
            names = [o.type for o in g.objects if role in o.roles]
            lines.append(f"{ROLE_MARK[role]} **{title}:** {', '.join(names) if names else '—'}")
        lines.append("")
        lines += ["", "**Relations:** " + ("; ".join(f"{a} *{r}* {b}" for a, r, b in g.relations) or "—")]
        self.graph_md.content = "\n\n".join(lines)
        threading.Thread(target=self._draw_graph, args=(g,), daemon=True).start()
        types = tuple(o.type for o in g.objects) or ("-",)
        self.role_object.options = types
        ids = tuple(o.id for o in gen.plan.objects) or ("-",)
        self.c_object.options = ids
        self.c_target.options = ids
        self.c_text.value = gen.plan.constraints
        self.show_constraints()

    def _draw_graph(self, graph: TaskGraph) -> None:
        self.graph_img.image = render_graph(graph)
        self.graph_img.visible = True

    def show_constraints(self) -> None:
        gen = self.state.gen
        if gen is None or self.c_object.value not in {o.id for o in gen.plan.objects}:
            return
        cs = read_constraints(gen.plan.constraints, [o.id for o in gen.plan.objects],
                              lambda oid: catalogue().default_placement(gen.plan.object(oid).type)
                              if gen.plan.object(oid).type in catalogue() else "edge")
        oc = cs.objects[self.c_object.value]
        items = [f"- `{oc.placement}`"] + [f"- `{c.name}` → `{c.target}`" for c in oc.relations]
        self.c_list.content = f"**{oc.object_id}**\n\n" + "\n".join(items)

    def show_metrics(self, gen: Generation | None = None) -> None:
        gen = gen or self.state.gen
        m = scene_metrics(gen.plan, gen.layout)
        e = layout_energy(gen.plan, gen.layout.placements).as_dict()
        self.metrics_md.content = (
            "| metric | value |\n| --- | --- |\n"
            f"| CNT | {100 * m.cnt:.0f} % |\n| SR | {100 * m.sr:.0f} % |\n| NAV | {100 * m.nav:.1f} % |\n"
            f"| Key_NAV | {100 * m.key_nav:.0f} % |\n| OOB | {100 * m.oob:.0f} % |\n| collisions | {m.collisions} |\n"
            f"| constraints met | {100 * m.constraint_satisfaction:.0f} % |\n"
            f"| energy (total) | {e['total']:.3f} |")

    # ---- picking and dragging ---------------------------------------------------------------------

    def pick(self, object_id: str) -> None:
        gen = self.state.gen
        if gen is None:
            return
        obj = next((o for o in gen.scene.all_objects() if o.id == object_id), None)
        if obj is None:
            return
        cat = catalogue()
        t = cat.host(obj.type) if obj.type in cat else None
        flags = ", ".join(k for k, v in (t.flags.items() if t else []) if v) or "—"
        self.picked_md.content = (f"**{obj.id}** ({obj.type}, {obj.role})\n\nasset `{obj.asset_id}` · "
                                  f"{obj.size.x:.2f} × {obj.size.z:.2f} × {obj.size.y:.2f} m · at ({obj.x:.2f}, "
                                  f"{obj.z:.2f}) facing {obj.rotation:.0f}°\n\n{flags}")
        if object_id in {o.id for o in gen.plan.objects}:
            self.c_object.value = object_id
            self.show_constraints()
            self._attach_controls(obj)

    def _attach_controls(self, obj) -> None:
        if self.controls is not None:
            self.controls.remove()
        self.controls = self.client.scene.add_transform_controls(
            "/drag", scale=0.6, active_axes=(True, False, True), position=world(obj.x, 0.02, obj.z),
            disable_sliders=True)
        self.controls.on_update(lambda event: self.dragged(obj.id) if getattr(event, "phase", None) == "end"
                                else self.dragging(obj.id))

    def dragging(self, object_id: str) -> None:
        """While the gizmo moves: re-score the metrics live (at most every 0.3 s), without redrawing."""
        now = time.perf_counter()
        if now - self._last_live < LIVE_RESCORE_S or self.state.gen is None:
            return
        self._last_live = now
        x, _, neg_z = self.controls.position
        gen = self.state.gen
        before = gen.layout.placement(object_id)
        moved = self.pipeline.move(gen, object_id, float(x), float(-neg_z), before.rotation, self.state.seed)
        self.show_metrics(moved)

    def dragged(self, object_id: str) -> None:
        gen = self.state.gen
        x, _, neg_z = self.controls.position
        before = next(p for p in gen.layout.placements if p.id == object_id)
        rotation = (round((before.rotation + rotation_of(self.controls.wxyz)) / 90) * 90) % 360
        new = self.pipeline.move(gen, object_id, float(x), float(-neg_z), rotation, self.state.seed)
        self.state.edits.append(Edit("move", object_id, [before.x, before.z, before.rotation],
                                     [round(float(x), 3), round(float(-neg_z), 3), rotation]))
        self.state.gen = new
        self.redraw()
        self.show_metrics()
        self.say(f"Moved `{object_id}` to ({x:.2f}, {-neg_z:.2f}); metrics re-scored. "
                 f"{len(self.state.edits)} designer edit(s) in this session.")

    # ---- constraint editing -----------------------------------------------------------------------

    def apply_text(self, text: str) -> None:
        gen = self.state.gen
        if gen is None:
            return
        ids = [o.id for o in gen.plan.objects]
        cs = read_constraints(text, ids)
        if cs.warnings:
            self.c_message.content = "**Error:** Edit not applied:\n\n" + "\n".join(f"- {w}" for w in cs.warnings)
            return
        before = gen.plan.constraints
        self.state.edits.append(Edit("constraints", "plan", before, text))
        kept = kept_before_edit(gen, gen.plan.model_copy(update={"constraints": text}))
        self._run(lambda obs: self.pipeline.replan(gen, text, self.state.seed, self.state.solver, obs), fresh=False)
        moved = [p.id for p in self.state.gen.layout.placements
                 if (q := gen.layout.placement(p.id)) is None or (q.x, q.z, q.rotation) != (p.x, p.z, p.rotation)]
        self.c_message.content = (f"Re-placed after the edit ({len(kept)} objects before the edited one kept); "
                                  f"moved: {', '.join(moved) or 'nothing'}.")

    def _edit_object(self, change) -> None:
        gen = self.state.gen
        if gen is None or self.c_object.value not in {o.id for o in gen.plan.objects}:
            return
        ids = [o.id for o in gen.plan.objects]
        cs = read_constraints(gen.plan.constraints, ids)
        change(cs.objects[self.c_object.value])
        self.apply_text(write_constraints(cs))

    def add_constraint(self) -> None:
        name, target = self.c_type.value, self.c_target.value

        def change(oc):
            if name in GLOBALS:
                oc.placement = name
            elif target == oc.object_id:
                self.c_message.content = "**Error:** An object cannot be constrained to itself."
                raise _Rejected
            else:
                oc.relations.append(Constraint(name, target))
        with contextlib.suppress(_Rejected):
            self._edit_object(change)

    def clear_relations(self) -> None:
        self._edit_object(lambda oc: oc.relations.clear())

    # ---- task graph corrections -------------------------------------------------------------------

    def _graph_edit(self, objects: list[TaskObject], note: str) -> None:
        gen = self.state.gen
        graph = gen.task_graph.model_copy(update={"objects": objects})
        self.state.edits.append(Edit("task-graph", note, [o.model_dump() for o in gen.task_graph.objects],
                                     [o.model_dump() for o in objects]))
        self.state.gen = Generation(graph, gen.room_plan, gen.plan, gen.layout, gen.scene)
        self.refresh_panels()
        self.say(f"Task graph edited ({note}). Press **Regenerate from graph** to rebuild the room.")

    def set_role(self) -> None:
        gen = self.state.gen
        if gen is None:
            return
        roles = [r.strip() for r in self.role_choice.value.split("+")]
        objects = [TaskObject(type=o.type, roles=roles) if o.type == self.role_object.value else o
                   for o in gen.task_graph.objects]
        self._graph_edit(objects, f"{self.role_object.value} -> {self.role_choice.value}")

    def add_object(self) -> None:
        gen = self.state.gen
        name = self.new_object.value.strip()
        cat = catalogue()
        found = cat.lexicon.get(name.lower(), (name,) if name in cat else None)
        if gen is None or not found:
            self.say(f"**Error:** Unknown object type {name!r}: use an AI2-THOR type or a common name (fridge, sofa...).")
            return
        self._graph_edit(gen.task_graph.objects + [TaskObject(type=found[0], roles=["inference"])], f"+{found[0]}")

    def remove_object(self) -> None:
        gen = self.state.gen
        if gen is None:
            return
        objects = [o for o in gen.task_graph.objects if o.type != self.role_object.value]
        self._graph_edit(objects, f"-{self.role_object.value}")

    def regenerate(self) -> None:
        gen = self.state.gen
        if gen is None:
            return
        graph: TaskGraph = gen.task_graph
        keep = {o.type for o in graph.objects}
        graph = graph.model_copy(update={"relations": [r for r in graph.relations if r[0] in keep and r[2] in keep]})
        self._run(lambda obs: self.pipeline.generate_from_graph(graph, self.state.seed, self.state.solver, obs),
                  fresh=False)

    # ---- storing and exporting --------------------------------------------------------------------

    def accept(self) -> None:
        gen = self.state.gen
        if gen is None:
            self.say("**Error:** Nothing to save yet: generate a scene first.")
            return
        name = self.save_name.value.strip() or gen.task_graph.instruction[:60]
        if self.state.scene_id is None:
            sid, number = self.store.create_scene(name, gen.scene, self.state.seed, self.state.solver,
                                                  self.state.edits)
            self.state.scene_id = sid
        else:
            sid = self.state.scene_id
            number = self.store.add_version(sid, name, gen.scene, self.state.seed, self.state.solver, self.state.edits)
        self.state.edits = []
        self.list_scenes()
        self.say(f"Saved as scene {sid}, version {number} (“{name}”).")

    def list_scenes(self) -> None:
        scenes = self.store.list_scenes()
        self.stored.options = tuple(f"{s['id']}: {s['name'][:50]}" for s in scenes) or ("-",)
        self.list_versions()

    def list_versions(self) -> None:
        sid = self._selected_scene()
        versions = self.store.versions(sid) if sid is not None else []
        self.version.options = tuple(f"v{v['number']}: {v['name'][:40]}" for v in versions) or ("-",)
        if versions:
            self.version.value = self.version.options[-1]

    def _selected_scene(self) -> int | None:
        value = self.stored.value
        return int(value.split(":")[0]) if value and value != "-" else None

    def open_version(self) -> None:
        sid = self._selected_scene()
        if sid is None or self.version.value == "-":
            self.say("**Error:** No stored scene selected.")
            return
        number = int(self.version.value.split(":")[0].removeprefix("v"))
        scene = self.store.scene(sid, number)
        try:
            gen = generation_of(scene)
        except ValueError as e:
            self.say(f"**Error:** {e}")
            return
        self._run(lambda _obs: gen, fresh=True)
        self.state.scene_id = sid
        self.instruction.value = gen.task_graph.instruction
        self.say(f"Opened scene {sid}, version {number}: {len(gen.layout.placements)} objects.")

    def download(self, kind: str) -> None:
        gen = self.state.gen
        if gen is None:
            return
        if kind == "house":
            self.client.send_file_download("house.json", json.dumps(to_house(gen.scene), indent=2).encode(),
                                           save_immediately=True)
        else:
            self.client.send_file_download("scene.glb", to_glb(gen.scene), save_immediately=True)


class _Rejected(Exception):
    pass
