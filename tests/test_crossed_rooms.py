"""Rooms the robot crosses (`Room.crossed`: an apartment's rooms with several doors): the floorplan marks them, and
a placer's reach guard and repairs keep their doors joined, counting a door cut off like a task object out of
reach; other rooms are judged as before."""

from __future__ import annotations

import numpy as np

from models.datasets import load_dataset
from models.placement.candidates import PlacedObject
from models.placement.problem import PlacementProblem
from models.placement.reach import Reach
from models.values import Room
from models.values.room import Opening

DOOR = dict(width=1.0, asset_id="Doorway_2", height=2.07, sill=0.0)
ROOM = Room(type="living room", width=4, depth=4, doors=[Opening(wall="west", center=2.0, **DOOR),
                                                         Opening(wall="east", center=2.0, **DOOR)], crossed=True)


def shelf(zmax: float) -> PlacedObject:
    """A shelf across the room from the south wall to `zmax`."""
    return PlacedObject("shelf", 2.0, zmax / 2, 0.0, 0.4, zmax, np.array([1.8, 0.0, 2.2, zmax]), None)


def reach(room: Room) -> Reach:
    plan = next(iter(load_dataset("seen"))).plan
    return Reach(PlacementProblem.from_plan(plan.model_copy(update={"room": room})))


def test_a_door_cut_off_counts_out_of_reach_in_a_crossed_room_only():
    crossed, plain = reach(ROOM), reach(ROOM.model_copy(update={"crossed": None}))
    assert crossed.unreachable([shelf(4.0)]) == ["door|1"] and crossed.unreachable([shelf(3.0)]) == []
    assert plain.unreachable([shelf(4.0)]) == []  # a room not crossed: either door will do
    one_door = reach(ROOM.model_copy(update={"doors": ROOM.doors[:1]}))
    assert one_door.unreachable([shelf(4.0)]) == [] and not one_door.gates
    # the reach guard refuses the wall between the doors in the crossed room, not in the other
    blocked = crossed.blocked([])
    reachable = np.ones_like(blocked)  # an energy set-up's grid (from every door): the crossed room floods its own
    assert list(crossed.keeping([], [shelf(4.0), shelf(3.0)], blocked, reachable)) == [False, True]
    assert list(plain.keeping([], [shelf(4.0)], blocked, reachable)) == [True]
    assert crossed.gate_centres == {"door|1": (3.7, 2.0)}  # where the repairs look for objects in the way


def test_the_floorplan_marks_the_rooms_with_several_doors_as_crossed(pipeline):
    apartment = pipeline.generate_apartment("Put a chilled bread on the counter", None, seed=3)
    rooms = [plan.room for plan in apartment.plans]
    assert any(r.crossed for r in rooms) and all(bool(r.crossed) == (len(r.doors) > 1) for r in rooms)


def test_plan2place_keeps_a_crossed_living_room_s_doors_joined_at_the_first_layout(monkeypatch, tmp_path,
                                                                                   capsys):
    """Apartment 0 of `bench generate --room-type apartment`: without the flag, Plan2Place's living room (6.75 x
    4.1 m, 13 objects) cuts a door off from the other; with it, the first layout joins them."""
    import app.pipeline as pipeline_module
    from app.pipeline import Pipeline
    from models.energy.navigation import doors_joined
    from models.placement.greedy import WALLS_OFF_DOOR
    from models.scene.assemble import footprint_boxes

    monkeypatch.setattr(pipeline_module, "PASSABLE_TRIES", 1)
    pipeline = Pipeline(solver="plan2place")
    apartment = pipeline.generate_apartment("Put the baseball bat on the bed", None, seed=0)
    plan, layout = next((p, la) for p, la in zip(apartment.plans, apartment.layouts) if p.room.type == "living room")
    assert plan.room.crossed and doors_joined(plan.room, footprint_boxes(layout.placements)) and not layout.warnings
    steps = []
    assert pipeline.place(plan, layout.seed, observer=steps.append).placements == layout.placements
    assert WALLS_OFF_DOOR in [s.why for s in steps]  # the studio says why a step took another pose
    unflagged = plan.model_copy(update={"room": plan.room.model_copy(update={"crossed": None})})
    steps = []
    assert not doors_joined(plan.room, footprint_boxes(pipeline.place(unflagged, layout.seed, observer=steps.append)
                                                       .placements))
    assert WALLS_OFF_DOOR not in [s.why for s in steps]
    # `h3ds place` reads the optional field from the plan JSON (written without it where it is absent)
    from app.cli import main
    from models.values import Layout

    for name, p in (("flagged", plan), ("unflagged", unflagged)):
        (tmp_path / f"{name}.json").write_text(p.model_dump_json(exclude_none=True))
    assert '"crossed"' not in (tmp_path / "unflagged.json").read_text()
    for name, joined in (("flagged", True), ("unflagged", False)):
        assert main(["place", str(tmp_path / f"{name}.json"), "--seed", str(layout.seed)]) == 0
        placed = Layout.model_validate_json(capsys.readouterr().out).placements
        assert doors_joined(plan.room, footprint_boxes(placed)) == joined


def test_restore_access_rejoins_a_door_cut_off_in_a_crossed_room(monkeypatch):
    """The apartment of "Pick up a bowl while turning on a desk lamp" (seed 66): Plan2Place's steps leave a crossed
    room's second door cut off; the restore-access repair, looking for what stands nearest the doorway too, moves
    one piece and every door is reached again, its step saying so."""
    import app.pipeline as pipeline_module
    import models.placement.repair as repair_module
    from app.pipeline import Pipeline

    seen, restore = [], repair_module.restore_access

    def watched(ep, observer=None):
        before = ep.reach.unreachable(ep.placed)
        steps = []
        moved = restore(ep, lambda s: (steps.append(s), observer and observer(s)))
        if ep.reach.gates:
            seen.append((before, moved, ep.reach.unreachable(ep.placed), [s.why for s in steps]))
        return moved

    monkeypatch.setattr(repair_module, "restore_access", watched)
    monkeypatch.setattr(pipeline_module, "PASSABLE_TRIES", 1)
    Pipeline(solver="plan2place").generate_apartment("Pick up a bowl while turning on a desk lamp", None, seed=66)
    cut = [s for s in seen if any(o.startswith("door|") for o in s[0])]
    assert cut and all(moved and after == [] for _, moved, after, _ in cut)
    assert all(why == ["clearing the robot's way to the task objects and doors"] * len(moved)
               for _, moved, _, why in cut)


def test_a_single_room_with_two_doors_is_kept_passable(monkeypatch):
    """ALFRED's "Put a salt shaker in a drawer next to the oven." in a living room (seed 19, the vrpose bench's): the
    room planner marks a single room with two doors crossed, and Plan2Place's first layout keeps them joined. Without
    the flag, that layout splits the room between its doors, the robot (entering by the door on the drawer's side)
    cannot reach the salt shaker, and the pipeline's check places the room again until a layout (seed 21) joins them.
    (Z3's window, which here happens to move the split away by chance, is off for that part: the check is under test.)"""
    import app.pipeline as pipeline_module
    from app.pipeline import Pipeline
    from models.energy.navigation import doors_joined
    from models.exports.procthor_house import to_house
    from models.interaction import check_plan, robot_plan
    from models.placement import exact_finish
    from models.scene.assemble import assemble_scene, footprint_boxes
    from models.values import TaskGraph

    graph = TaskGraph.model_validate({
        "instruction": "Put a salt shaker in a drawer next to the oven.", "room_type": "living room",
        "task_type": "pick_and_place_simple", "relations": [["SaltShaker", "placed_at", "Drawer"]],
        "objects": [{"type": "SaltShaker", "roles": ["key"]}, {"type": "Drawer", "roles": ["key", "anchor"]}]})
    pipeline, default_tries = Pipeline(solver="plan2place"), pipeline_module.PASSABLE_TRIES

    def judged(layout):
        scene = assemble_scene(gen.room_plan, layout, graph, 19, gen.plan.constraints)
        house = to_house(scene)
        joined = doors_joined(gen.plan.room, footprint_boxes(layout.placements))
        return layout.seed, joined, check_plan(house, robot_plan(scene, house), graph).ok

    gen = pipeline.generate_from_graph(graph, seed=19)
    assert gen.plan.room.crossed and len(gen.plan.room.doors) == 2
    assert judged(gen.layout) == (19, True, True) and gen.layout.warnings == []
    unflagged = gen.plan.model_copy(update={"room": gen.plan.room.model_copy(update={"crossed": None})})
    monkeypatch.setattr(exact_finish, "ONE_MORE_AT", 0)
    monkeypatch.setattr(pipeline_module, "PASSABLE_TRIES", 1)
    once = pipeline.place_passable(unflagged, 19)
    assert judged(once) == (19, False, False) and "cuts one of the room's doors off" in once.warnings[0]
    monkeypatch.setattr(pipeline_module, "PASSABLE_TRIES", default_tries)
    assert judged(pipeline.place_passable(unflagged, 19)) == (21, True, True)
