"""The whole pipeline, as one object the CLI, the API and the studio all drive.

instruction -> TaskGraph -> RoomPlan -> ConstraintPlan -> Layout -> Scene -> exports

Every stage is replaceable (pass another parser, planner, writer or solver name); every stage's output
is a typed value, so any of them can be saved, edited and fed back in.
"""

from __future__ import annotations

import json
from collections.abc import Collection
from dataclasses import dataclass
from pathlib import Path

from models.energy.navigation import doors_joined
from models.geometry import Footprint, overlap_area
from models.language import InstructionParser
from models.language.combined import make_parser
from models.metrics.placement import AREA_TOL
from models.placement import PlacementProblem, StepObserver, get_solver
from models.placement.base import Fixed
from models.placement.stepping import Stepping
from models.planning import ConstraintWriter, RoomPlanner
from models.planning.apartment_planner import ApartmentPlanner
from models.scene import assemble_scene
from models.scene.apartment import assemble_apartment
from models.scene.assemble import footprint_boxes
from models.values import ConstraintPlan, Layout, Placement, RoomPlan, Scene, TaskGraph, Timing
from models.values.apartment import Apartment
from models.world import requested_room_type


@dataclass(frozen=True)
class Generation:
    """Every stage's value for one instruction."""

    task_graph: TaskGraph
    room_plan: RoomPlan
    plan: ConstraintPlan
    layout: Layout
    scene: Scene


PASSABLE_TRIES = 4  # layouts tried for a room with several doors until one keeps them joined (`place_passable`)


class Pipeline:
    def __init__(self, parser: InstructionParser | None = None, planner: RoomPlanner | None = None,
                 writer: ConstraintWriter | None = None, solver: str | None = None):
        self.parser = parser or make_parser()  # the default parser (models/language/combined.py)
        self.planner = planner or RoomPlanner()
        self.writer = writer or ConstraintWriter()
        self.solver = solver

    def parse(self, instruction: str, room_type: str | None = None) -> TaskGraph:
        """The task graph; `room_type` None or "infer": the parser infers it from the instruction."""
        return self.parser.parse(instruction, requested_room_type(room_type))

    def place(self, plan: ConstraintPlan, seed: int = 0, solver: str | None = None,
              observer: StepObserver | None = None, keep: Fixed | None = None) -> Layout:
        return get_solver(solver or self.solver).solve(plan, seed=seed, observer=observer, fixed=keep)

    def stepping(self, plan: ConstraintPlan, seed: int = 0, solver: str | None = None,
                 keep: Fixed | None = None) -> Stepping:
        """`place` as an iterator of its steps (models.placement.stepping); the layout is its `layout` after them."""
        return Stepping(get_solver(solver or self.solver), plan, seed=seed, fixed=keep)

    def generate(self, instruction: str, room_type: str | None, seed: int = 0, solver: str | None = None,
                 observer: StepObserver | None = None) -> Generation:
        graph = self.parse(instruction, room_type)
        return self.generate_from_graph(graph, seed, solver, observer)

    def generate_from_graph(self, graph: TaskGraph, seed: int = 0, solver: str | None = None,
                            observer: StepObserver | None = None) -> Generation:
        room_plan = self.planner.plan(graph, seed=seed, plan_id=f"scene-{seed}")
        plan = self.writer.write(room_plan)
        layout = self.place_passable(plan, seed, solver, observer)
        scene = assemble_scene(room_plan, layout, graph, seed, plan.constraints)
        return Generation(graph, room_plan, plan, layout, scene)


    def generate_apartment(self, instruction: str, rooms: list[str] | None = None, seed: int = 0,
                           solver: str | None = None, observer: StepObserver | None = None) -> Apartment:
        """Several rooms joined by doors; the task's own room type is inferred from the instruction."""
        return self.generate_apartment_from_graph(self.parse(instruction, None), rooms, seed, solver, observer)

    def generate_apartment_from_graph(self, graph: TaskGraph, rooms: list[str] | None = None, seed: int = 0,
                                      solver: str | None = None, observer: StepObserver | None = None) -> Apartment:
        house = ApartmentPlanner(self.planner).plan(graph, rooms, seed=seed, plan_id=f"apartment-{seed}")
        plans = [self.writer.write(rp) for rp in house.room_plans]
        layouts = [self.place_passable(plan, seed, solver, observer) for plan in plans]
        return assemble_apartment(house, plans, layouts, graph, seed)

    def place_passable(self, plan: ConstraintPlan, seed: int = 0, solver: str | None = None,
                       observer: StepObserver | None = None, keep: Fixed | None = None) -> Layout:
        """`place` for a room with several doors: the robot may have to cross it from one door to another (a room of
        an apartment), or enters by one of them and must reach every task object from there (a single room), which
        no placer is asked for (Key_NAV asks for the task objects, from any door). While its furniture cuts a door
        off, the room is placed again with the next seed, up to PASSABLE_TRIES in all; if none keeps its doors
        joined, the first layout, with a warning. The layout records the seed it kept; the `observer` sees its
        steps; its timing counts every try. `keep`: poses every try keeps (a designer's re-plan)."""
        tries = []
        for k in range(PASSABLE_TRIES if len(plan.room.doors) > 1 else 1):
            steps: list = []
            layout = self.place(plan, seed + k, solver, steps.append if observer else None, keep)
            tries.append((layout, steps))
            if doors_joined(plan.room, footprint_boxes(layout.placements)):
                break
        else:
            layout, steps = tries[0]
            layout = layout.model_copy(update={"warnings": [*layout.warnings, (
                f"the furniture cuts one of the room's doors off from another in all {len(tries)} layouts tried "
                f"(seeds {seed}-{seed + len(tries) - 1}): the robot cannot cross the room")]})
        for step in steps:
            observer(step)
        spent = sum(t.timing.total_s for t, _ in tries)
        scale = spent / layout.timing.total_s if layout.timing.total_s else 1.0
        timing = Timing(total_s=spent, per_object_s=layout.timing.per_object_s * scale)
        return layout.model_copy(update={"timing": timing})

    def replan(self, gen: Generation, constraints: str, seed: int = 0, solver: str | None = None,
               observer: StepObserver | None = None) -> Generation:
        """The same room and objects with edited constraint text, placed again from the edited point:
        objects placed before the first one whose constraints changed keep their poses (and, as when it was
        generated, a room with several doors is placed again while its furniture cuts one off: `place_passable`)."""
        plan = gen.plan.model_copy(update={"constraints": constraints})
        layout = self.place_passable(plan, seed, solver, observer, keep=kept_before_edit(gen, plan))
        return Generation(gen.task_graph, gen.room_plan, plan, layout,
                          assemble_scene(gen.room_plan, layout, gen.task_graph, seed, constraints))

    def replace_around(self, gen: Generation, moved: Collection[str], seed: int = 0, solver: str | None = None,
                       observer: StepObserver | None = None) -> Generation:
        """Re-plan from a designer's moves: the `moved` objects stay where the designer put them and the
        placer places the others again around them, from the first moved object's point in its order on
        (see `kept_around_moves`; `place_passable` as in `replan`)."""
        layout = self.place_passable(gen.plan, seed, solver, observer, keep=kept_around_moves(gen, moved))
        return Generation(gen.task_graph, gen.room_plan, gen.plan, layout,
                          assemble_scene(gen.room_plan, layout, gen.task_graph, seed, gen.plan.constraints))

    def move(self, gen: Generation, object_id: str, x: float, z: float, rotation: float, seed: int = 0) -> Generation:
        """A designer's drag: one object at a new pose, everything else as it was."""
        placements = [p.model_copy(update={"x": round(x, 4), "z": round(z, 4), "rotation": rotation % 360})
                      if p.id == object_id else p for p in gen.layout.placements]
        layout = gen.layout.model_copy(update={"placements": placements})
        return Generation(gen.task_graph, gen.room_plan, gen.plan, layout,
                          assemble_scene(gen.room_plan, layout, gen.task_graph, seed, gen.plan.constraints))


def kept_before_edit(gen: Generation, edited: ConstraintPlan) -> Fixed:
    """Poses of the objects that the edited plan places before its first changed object."""
    before = PlacementProblem.from_plan(gen.plan).constraints.objects
    after = PlacementProblem.from_plan(edited)
    keep: Fixed = {}
    for o in after.order:
        if after.constraints.objects[o.id] != before.get(o.id):
            break
        p = gen.layout.placement(o.id)
        if p is not None:
            keep[o.id] = (p.x, p.z, p.rotation)
    return keep


def kept_around_moves(gen: Generation, moved: Collection[str]) -> Fixed:
    """The poses a re-plan around a designer's moves keeps: the `moved` objects' own, and those of the
    objects the placer puts before the first moved one that do not collide with a moved one (as the
    metrics count collisions); the rest is placed again."""
    moved = [m for m in dict.fromkeys(moved) if gen.layout.placement(m) is not None]
    if not moved:
        raise ValueError("nothing to re-place around: no moved object of this scene is placed")
    order = [o.id for o in PlacementProblem.from_plan(gen.plan).order]
    feet = {p.id: Footprint(p.x, p.z, p.size.x, p.size.z, p.rotation) for p in gen.layout.placements}
    keep: Fixed = {m: pose_of(gen.layout.placement(m)) for m in moved}
    for oid in order[:min(order.index(m) for m in moved)]:
        if oid in feet and all(overlap_area(feet[oid], feet[m]) <= AREA_TOL for m in moved):
            keep.setdefault(oid, pose_of(gen.layout.placement(oid)))
    return keep


def strangers(plan: ConstraintPlan, keep: Fixed) -> list[str]:
    """The ids of `keep` that are not objects of `plan` (a kept pose must be one of its objects')."""
    ids = {o.id for o in plan.objects}
    return [i for i in keep if i not in ids]


def outside(plan: ConstraintPlan, keep: Fixed) -> str:
    """What is wrong with `keep` for `plan`, naming each pose whose centre is outside its room (empty if none): a kept
    pose is placed as it is, so one outside the room would leave its object outside (most likely a unit or an axis
    swapped)."""
    w, d = plan.room.width, plan.room.depth
    far = [f"{i} at ({x}, {z})" for i, (x, z, _) in keep.items() if not (0 <= x <= w and 0 <= z <= d)]
    return f"poses outside the {w} x {d} m room of plan {plan.id}: {', '.join(far)}" if far else ""


def pose_of(p: Placement) -> tuple[float, float, float]:
    """(x, z, rotation) of a placement: what a kept pose is."""
    return p.x, p.z, p.rotation


def generation_of(scene: Scene) -> Generation:
    """Re-open a stored scene as a Generation (it carries its room plan and constraint text)."""
    if scene.room_plan is None or scene.task_graph is None:
        raise ValueError(f"scene {scene.id} was stored without its room plan; it can be viewed but not edited")
    rp = scene.room_plan
    plan = ConstraintPlan(id=rp.id, room=rp.room, objects=rp.objects, constraints=scene.constraints or "")
    sizes = {o.id: o for o in rp.objects}
    placements = [Placement(id=o.id, type=o.type, x=o.x, z=o.z, rotation=o.rotation, size=sizes[o.id].size)
                  for o in scene.objects if o.id in sizes]
    layout_prov = next((p for p in scene.provenance if p.stage == "layout"), None)
    layout = Layout(plan_id=plan.id, solver=layout_prov.method if layout_prov else "stored",
                    seed=layout_prov.seed or 0 if layout_prov else 0, placements=placements,
                    unplaced=[u for u in scene.unplaced if u.id in sizes], warnings=[],
                    timing=Timing(total_s=0.0, per_object_s=0.0), provenance=layout_prov)
    return Generation(scene.task_graph, rp, plan, layout, scene)


def room_generation(apartment: Apartment, k: int, graph: TaskGraph | None = None) -> Generation:
    """Room `k` of an apartment (floorplan order) as a single room in its own frame, to edit like one; the edited
    room goes back with models.scene.apartment.with_room. `graph`: a corrected task graph it carries instead of
    the apartment's (a designer's corrections, not yet regenerated)."""
    return Generation(graph or apartment.task_graph, apartment.plan.room_plans[k], apartment.plans[k],
                      apartment.layouts[k], apartment.scenes[k])


def dump(value) -> str:
    """A value as the JSON of interfaces.md (unset optional fields left out)."""
    return json.dumps(value.model_dump(mode="json", exclude_none=True), indent=2)


def _write_texts(out_dir: Path, texts: dict[str, str]) -> list[Path]:
    paths = []
    for name, text in texts.items():
        (out_dir / name).parent.mkdir(parents=True, exist_ok=True)
        (out_dir / name).write_text(text + "\n")
        paths.append(out_dir / name)
    return paths


def write_apartment(apartment: Apartment, out_dir: Path) -> list[Path]:
    """`generate --room-type apartment`: the task graph, the floorplan, rooms/<n>-<type>/plan.json and
    layout.json per room (each one readable by `h3ds place`), house.json and scene.glb of the whole house, and
    apartment.json, the whole value (what `h3ds edit` and the API's POST /edit and /scenes take)."""
    from models.exports.apartment import apartment_glb, apartment_house

    texts = {"task_graph.json": dump(apartment.task_graph), "floorplan.json": json.dumps(
                 {**json.loads(dump(apartment.floorplan)), "assignment": apartment.plan.assignment}, indent=2),
             "navigation.json": json.dumps({"key_nav": apartment.key_nav, "e_nav": apartment.e_nav,
                                            **apartment.path.model_dump(mode="json")}, indent=2),
             "house.json": json.dumps(apartment_house(apartment), indent=2), "apartment.json": dump(apartment)}
    for hr, plan, layout in zip(apartment.floorplan.rooms, apartment.plans, apartment.layouts):
        folder = f"rooms/{hr.id.split('|')[-1]}-{hr.room.type.replace(' ', '-')}"
        texts[f"{folder}/plan.json"] = dump(plan)
        texts[f"{folder}/layout.json"] = dump(layout)
    paths = _write_texts(out_dir, texts)
    (out_dir / "scene.glb").write_bytes(apartment_glb(apartment))
    return paths + [out_dir / "scene.glb"]


def write_generation(gen: Generation, out_dir: Path) -> list[Path]:
    """The five files of `h3ds generate` (interfaces.md) and scene.json, the Scene with what it was made from
    (what `h3ds edit` and the API's POST /edit and /scenes take)."""
    from models.exports.glb import to_glb  # trimesh takes ~0.6 s to import: only when a GLB is written
    from models.exports.procthor_house import to_house

    out_dir.mkdir(parents=True, exist_ok=True)
    texts = {"task_graph.json": dump(gen.task_graph), "plan.json": dump(gen.plan), "layout.json": dump(gen.layout),
             "house.json": json.dumps(to_house(gen.scene), indent=2), "scene.json": dump(gen.scene)}
    paths = _write_texts(out_dir, texts)
    (out_dir / "scene.glb").write_bytes(to_glb(gen.scene))
    paths.append(out_dir / "scene.glb")
    return paths
