"""Robot task plans as AI2-THOR actions, run on the exported house's symbolic state (ALFRED semantics)."""

from __future__ import annotations

import json

import pytest
from interaction_scenes import COOL, HEAT_SLICED, LAMP_ONLY, LOOK, SIMPLE, kitchen

from models.exports.procthor_house import to_house
from models.interaction import SymbolicState, check_plan, execute_step, robot_plan
from models.values.interaction import RobotPlan

THOR_ACTIONS = {"TeleportFull", "OpenObject", "CloseObject", "PickupObject", "PutObject", "ToggleObjectOn",
                "ToggleObjectOff", "SliceObject"}


def house_ids(house: dict) -> set[str]:
    return {o["id"] for o in house["objects"]} | {c["id"] for o in house["objects"] for c in o.get("children", [])}


def plan_for(task, drop=()):
    scene = kitchen(task, drop)
    house = to_house(scene)
    return scene, house, robot_plan(scene, house)


def without(plan: RobotPlan, *indices: int) -> RobotPlan:
    steps = [s for s in plan.steps if s.index not in indices]
    return plan.model_copy(update={"steps": [s.model_copy(update={"index": i}) for i, s in enumerate(steps)]})


@pytest.mark.parametrize("task", [SIMPLE, COOL, HEAT_SLICED, LOOK, LAMP_ONLY],
                         ids=lambda t: t.task_type + ("" if t.relations else " (the lamp alone)"))
def test_every_task_type_reaches_its_goal_with_ids_of_the_house(task):
    scene, house, plan = plan_for(task)
    assert plan.problems == []
    ids = house_ids(house)
    for step in plan.steps:
        assert step.action["action"] in THOR_ACTIONS
        if step.action["action"] == "TeleportFull":
            assert set(step.action) == {"action", "position", "rotation", "horizon", "standing"}
        else:
            assert set(step.action) >= {"action", "objectId", "forceAction"}
            oid = step.action["objectId"]
            # every id is in the exported house, except a slice, which SliceObject creates
            assert oid in ids or oid == plan.objects.get("slice"), oid
    json.dumps([s.action for s in plan.steps])  # AI2-THOR kwargs: plain JSON
    check = check_plan(house, plan, task)
    assert check.ok, check.failure
    assert check.goal_conditions and all(check.goal_conditions.values())
    assert [r.ok for r in check.steps] == [True] * len(plan.steps)


def test_the_lamp_alone_is_switched_on_and_nothing_is_picked_up():
    """"Turn on the lamp": the parsers name only the lamp, so the plan walks to it and switches it on (it used to
    try to pick the lamp up), and the goal asks for the light alone; without the switch it does not hold."""
    _, house, plan = plan_for(LAMP_ONLY)
    assert [s.action["action"] for s in plan.steps] == ["TeleportFull", "ToggleObjectOn"]
    assert plan.objects == {"lamp": "FloorLamp|1|0"} and plan.problems == []
    check = check_plan(house, plan, LAMP_ONLY)
    assert check.ok and list(check.goal_conditions) == ["a FloorLamp within reach is on"]
    assert not check_plan(house, without(plan, 1), LAMP_ONLY).ok
    _, house, plan = plan_for(LAMP_ONLY, drop=("FloorLamp",))
    assert plan.steps == [] and plan.problems == ["no FloorLamp in the exported house (the task's lamp)"]
    anchor_only = [LAMP_ONLY.objects[0].model_copy(update={"roles": ["anchor"]})]
    nothing = LAMP_ONLY.model_copy(update={"objects": anchor_only})  # no relation, no key object: nothing to act on
    assert robot_plan(None, house, nothing).problems == ["the task graph names no object to act on"]


def test_cool_plan_is_alfreds_sequence():
    _, _, plan = plan_for(COOL)
    names = [s.action["action"] for s in plan.steps]
    fridge = plan.objects["fridge"]
    assert fridge == "Fridge|1|0"
    on_fridge = [s.action["action"] for s in plan.steps if s.action.get("objectId") == fridge]
    assert on_fridge == ["OpenObject", "PutObject", "CloseObject", "OpenObject", "CloseObject"]
    assert names[-1] == "PutObject" and plan.steps[-1].action["objectId"] == plan.objects["receptacle"]


def test_heat_sliced_plan_slices_with_a_knife_then_heats_the_slice():
    _, _, plan = plan_for(HEAT_SLICED)
    names = [s.action["action"] for s in plan.steps]
    assert names.index("SliceObject") < names.index("ToggleObjectOn") < names.index("ToggleObjectOff")
    slice_pick = [s for s in plan.steps if s.action["action"] == "PickupObject"
                  and s.action["objectId"] == plan.objects["slice"]]
    assert slice_pick and plan.objects["slice"].endswith("|AppleSliced_1")


def test_missing_fridge_is_reported_and_fails_the_check():
    scene, house, plan = plan_for(COOL, drop=("Fridge",))
    assert any("no Fridge" in p for p in plan.problems)
    check = check_plan(house, plan, COOL)
    assert not check.ok and "cooled" in check.failure and "no Fridge" in check.failure


def test_missing_receptacle_fails():
    _, house, plan = plan_for(HEAT_SLICED, drop=("SinkBasin",))
    check = check_plan(house, plan, HEAT_SLICED)
    assert not check.ok and "SinkBasin" in check.failure


def test_wrong_order_put_before_open_fails_at_that_step():
    _, house, plan = plan_for(COOL)
    steps = list(plan.steps)
    k = next(i for i, s in enumerate(steps) if s.action["action"] == "OpenObject")
    steps[k], steps[k + 1] = steps[k + 1], steps[k]
    swapped = plan.model_copy(update={"steps": [s.model_copy(update={"index": i}) for i, s in enumerate(steps)]})
    check = check_plan(house, swapped, COOL)
    assert not check.ok and "closed" in check.failure and check.failure.startswith(f"step {k} PutObject")
    assert check.steps[-1].ok is False and len(check.steps) == k + 1


def test_not_closing_the_fridge_does_not_cool():
    _, house, plan = plan_for(COOL)
    cooling = next(s.index for s in plan.steps if "cools" in s.description)
    skipped = without(plan, cooling, cooling + 1)  # no close (cooling) and no re-open
    check = check_plan(house, skipped, COOL)
    assert not check.ok and check.failure.startswith("goal not met") and "cooled" in check.failure


def test_not_switching_the_microwave_on_does_not_heat():
    _, house, plan = plan_for(HEAT_SLICED)
    on = next(s.index for s in plan.steps if s.action["action"] == "ToggleObjectOn")
    check = check_plan(house, without(plan, on, on + 1), HEAT_SLICED)
    assert not check.ok and "heated" in check.failure


def test_dropping_the_last_put_leaves_the_object_unplaced():
    _, house, plan = plan_for(SIMPLE)
    check = check_plan(house, without(plan, len(plan.steps) - 1), SIMPLE)
    assert not check.ok and "put in/on a CounterTop" in check.failure


def test_empty_plan_earns_nothing_even_if_the_object_starts_on_its_receptacle():
    put_bread = COOL.model_copy(update={"task_type": "pick_and_place_simple",
                                        "relations": [("Bread", "placed_at", "CounterTop")]})
    _, house, plan = plan_for(put_bread)
    assert check_plan(house, plan, put_bread).ok  # the bread starts on the counter: the real plan moves it
    empty = plan.model_copy(update={"steps": []})
    check = check_plan(house, empty, put_bread)
    assert not check.ok and "the plan has steps" in check.failure


def test_actions_are_refused_as_ai2thor_refuses_them():
    scene = kitchen(HEAT_SLICED)
    state = SymbolicState.from_house(to_house(scene))
    far = {"action": "PickupObject", "objectId": "Bread|surface|1|0", "forceAction": True}
    _, r = execute_step(state, far)
    assert not r.ok and "beyond reach" in r.message
    _, r = execute_step(state, {"action": "TeleportFull", "position": {"x": 2.5, "y": 0.95, "z": 2.5},
                                "rotation": {"x": 0, "y": 0, "z": 0}, "horizon": 30, "standing": True})
    assert not r.ok and "not free floor" in r.message  # inside the dining table
    _, r = execute_step(state, {"action": "Fly", "objectId": "Fridge|1|0"})
    assert not r.ok and "unknown action" in r.message
    # slicing without a knife
    plan = robot_plan(scene, to_house(scene))
    first_goto = plan.steps[0]
    s1, _ = execute_step(state, first_goto)
    s2, r = execute_step(s1, {"action": "PickupObject", "objectId": "Bread|surface|1|0", "forceAction": True})
    assert r.ok
    s3, r = execute_step(s2, {"action": "SliceObject", "objectId": "Bread|surface|1|0", "forceAction": True})
    assert not r.ok and "knife" in r.message
    assert state.held is None and s2.held == "Bread|surface|1|0"  # execute_step never changes its input


def test_microwave_only_heats_when_closed_and_on():
    scene = kitchen(HEAT_SLICED)
    house = to_house(scene)
    plan = robot_plan(scene, house)
    state = SymbolicState.from_house(house)
    for step in plan.steps:
        if step.action["action"] == "CloseObject" and "Microwave" in step.action["objectId"]:
            break
        state, r = execute_step(state, step)
        assert r.ok
    _, r = execute_step(state, {"action": "ToggleObjectOn", "objectId": "Microwave|surface|1|0", "forceAction": True})
    assert not r.ok and "closed" in r.message


def test_generated_scenes_plans_hold_or_say_why():
    from app.pipeline import Pipeline
    pipeline = Pipeline(solver="dfs")
    for instruction, room in [("Put a chilled bread on the counter", "kitchen"),
                              ("Put a heated slice of apple in the sink", "kitchen"),
                              ("Examine a credit card by the light of a floor lamp", "living room"),
                              ("Put the watch on the sofa", "living room")]:
        gen = pipeline.generate(instruction, room, seed=1)
        house = to_house(gen.scene)
        plan = robot_plan(gen.scene, house)
        check = check_plan(house, plan, gen.task_graph)
        assert check.ok == (not plan.problems), (instruction, plan.problems, check.failure)
        if not check.ok:
            assert check.failure


def test_knife_taken_from_a_non_receptacle_is_put_down_on_a_surface():
    from interaction_scenes import obj, on
    scene = kitchen(HEAT_SLICED, drop=("Knife",))
    sink = obj("sink-0", "Sink", 4.4, 4.6, 180, children=(on(0.8, "knife-0", "Knife", 4.4, 4.6, "inference"),))
    scene = scene.model_copy(update={"objects": [*scene.objects, sink]})
    house = to_house(scene)
    plan = robot_plan(scene, house)
    assert plan.problems == []
    puts = [s.action["objectId"] for s in plan.steps if s.action["action"] == "PutObject"]
    assert "Sink|1|0" not in puts  # AI2-THOR's Sink is not a receptacle (its basin is)
    assert check_plan(house, plan, HEAT_SLICED).ok


def test_an_object_walled_off_from_the_robot_is_reported():
    scene = kitchen(LOOK)
    house = to_house(scene)
    lamp = next(o for o in house["objects"] if o["id"].startswith("FloorLamp"))
    lamp["position"].update(x=0.4, z=0.3)
    wall = [{"id": f"CounterTop|9|{k}", "assetId": "Countertop_I_10x2", "position": {"x": x, "y": 0.47, "z": 1.2},
             "rotation": {"x": 0, "y": 0, "z": 0}, "children": []} for k, x in enumerate((1.52, 4.0))]
    house["objects"] += wall  # two counters across the room: the lamp's side is cut off from the robot's
    house["metadata"]["agent"]["position"].update(x=2.5, z=4.0)
    plan = robot_plan(scene, house)
    assert any("no free floor reachable" in p and "FloorLamp" in p for p in plan.problems)
    check = check_plan(house, plan, LOOK)
    assert not check.ok and "FloorLamp" in check.failure and "on" in check.failure


def test_execute_step_takes_the_plan_steps_json_form():
    scene = kitchen(COOL)
    house = to_house(scene)
    plan = json.loads(json.dumps(robot_plan(scene, house).model_dump(mode="json")))  # as it crosses the wire
    state = SymbolicState.from_house(json.loads(json.dumps(house)))
    for step in plan["steps"]:
        state, result = execute_step(state, step)
        assert result.ok and result.index == step["index"], result.message
    assert state.objects[plan["objects"]["target"]].cooled


def test_the_robot_enters_by_the_door_from_which_it_reaches_the_task_objects():
    """A room with two doors, a counter across it: the robot starts at the door on the fridge's side, not the first."""
    from models.scene.assemble import robot_start
    from models.values import Opening, Room, RoomPlan, SceneObject, Size

    room = Room(type="kitchen", width=4.0, depth=4.0, doors=[Opening(wall="south", center=1.0, width=1.0),
                                                             Opening(wall="north", center=3.0, width=1.0)])
    plan = RoomPlan(id="two-doors", room=room, objects=[])

    def placed(oid, type_name, x, z, w, d, role="context", children=()):
        return SceneObject(id=oid, type=type_name, asset_id="a", role=role, x=x, y=0.5, z=z, rotation=0.0,
                           size=Size(x=w, y=1.0, z=d), children=list(children))

    bread = placed("bread-0", "Bread", 0.5, 3.6, 0.2, 0.1, role="key")
    fridge = placed("fridge-0", "Fridge", 0.5, 3.6, 0.8, 0.7, children=[bread])  # a context host of a task object
    across = placed("counter-0", "CounterTop", 2.0, 1.6, 4.0, 0.6)
    north = robot_start(plan, [fridge, across])
    assert (north.z, north.rotation) == (4.0 - 0.6, 180)  # facing in from the north door
    assert robot_start(plan).z == 0.6  # nothing placed: the first door
    gap = across.model_copy(update={"x": 2.6, "size": Size(x=2.8, y=1.0, z=0.6)})
    assert robot_start(plan, [fridge, gap]).z == 0.6  # a way round the counter: both doors reach it, the first wins


def test_a_task_object_goes_on_the_part_of_its_host_the_robot_can_come_near():
    """A long counter whose west end is walled in by shelves: the bread (alone on it, then beside a context cup)
    leaves the middle or its slot for the end the robot reaches; a context object keeps its slot."""
    from models.scene.assemble import APPROACH, _far_from_reach, _spots
    from models.values import Opening, Placement, Room, Size, SurfaceObject

    room = Room(type="kitchen", width=6.0, depth=4.0, doors=[Opening(wall="south", center=5.0, width=1.0)])
    counter = Placement(id="counter-0", type="CounterTop", x=3.0, z=3.7, rotation=180.0, size=Size(x=5.6, y=0.9, z=0.6))
    shelves = Placement(id="shelf-0", type="ShelvingUnit", x=4.0, z=1.8, rotation=0.0, size=Size(x=0.4, y=2.0, z=3.6))
    far = _far_from_reach(room, [counter, shelves])
    small = Size(x=0.2, y=0.1, z=0.2)
    bread = SurfaceObject(id="bread-0", type="Bread", size=small, role="key", parent="counter-0")
    cup = SurfaceObject(id="cup-0", type="Cup", size=small, parent="counter-0")
    (alone,) = _spots(counter, [bread], far)
    assert far(3.0, 3.7) > APPROACH >= far(*alone) and alone[0] > 3.0  # off the middle, to the reachable east
    cup_first = _spots(counter, [cup, bread], far)  # in order, the bread's slot would be the walled-in west one
    assert far(*cup_first[1]) <= APPROACH < far(*cup_first[0]) and cup_first == _spots(counter, [cup, cup], far)[::-1]
    assert _spots(counter, [cup], far) == [(3.0, 3.7)]  # a context object alone stays in the middle
