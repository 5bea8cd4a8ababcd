"""The repairs after the last object: an object left out for want of room is placed after moving another;
task objects the robot cannot reach are made reachable by moving a few objects. Never a fixed one; each
move a step; a layout with nothing to repair is untouched."""

import numpy as np

from models.datasets import load_dataset
from models.metrics import scene_metrics
from models.placement.repair import make_room, restore_access
from models.placement.greedy import GreedySolver
from episode_support import finished


def _plan(pid, dataset="seen"):
    return next(r.plan for r in load_dataset(dataset) if r.plan.id == pid)


def test_unreachable_task_objects_are_made_reachable_and_each_move_is_a_step():
    plan = _plan("seen-00346")  # greedy walls off the garbage can and a side table
    ep = finished(plan)
    before = scene_metrics(plan, ep.layout("greedy", 0, 0.0))
    assert ep.reach.unreachable(ep.placed) and before.key_nav < 1
    steps = []
    moved = restore_access(ep, steps.append)
    after = scene_metrics(plan, ep.layout("greedy", 0, 0.0))
    assert moved and [s.object_id for s in steps] == moved
    assert not ep.reach.unreachable(ep.placed) and after.key_nav == 1.0  # the metric agrees
    assert after.collisions == 0 and after.oob == 0 and after.cnt == 1.0
    last = {s.object_id: (s.x, s.z, s.rotation) for s in steps}
    assert all((p.x, p.z, p.rotation) == last[p.id] for p in ep.placed if p.id in last)
    assert all(s.scores.max() == 1.0 and (s.scores == 1.0).sum() == 1 for s in steps)
    assert all(s.why == "clearing the robot's way to the task objects" for s in steps)  # the studio shows it


def test_a_reachable_layout_and_fixed_objects_are_left_as_they_are():
    plan = _plan("seen-00346")
    ep = finished(plan)
    restore_access(ep)
    poses = [(p.id, p.x, p.z, p.rotation) for p in ep.placed]
    assert restore_access(ep) == [] and [(p.id, p.x, p.z, p.rotation) for p in ep.placed] == poses
    # with every object fixed where greedy put it, nothing may move, even though access is blocked
    walled = finished(plan)
    fixed = {p.id: (p.x, p.z, p.rotation) for p in walled.placed}
    again = finished(plan, fixed)
    assert again.reach.unreachable(again.placed) and restore_access(again) == []


def test_the_greedy_solver_finishes_with_the_repair_unless_told_not_to():
    plan = _plan("seen-00395")  # greedy without its reach guard leaves both task objects out of reach
    plain = scene_metrics(plan, GreedySolver(repair=False, guard=False).solve(plan))
    repaired = scene_metrics(plan, GreedySolver(guard=False).solve(plan))
    assert plain.key_nav == 0 and repaired.key_nav == 1


def test_the_reach_guard_keeps_the_task_objects_reachable_while_placing_and_says_so():
    """The same plan with the guard and no repair: the step whose most wanted pose would wall off a task
    object takes another one, and its step says why."""
    plan = _plan("seen-00395")
    steps = []
    guarded = scene_metrics(plan, GreedySolver(repair=False).solve(plan, observer=steps.append))
    assert guarded.key_nav == 1 and guarded.cnt == 1 and guarded.collisions == 0
    assert [s.why for s in steps if s.why] == ["its most wanted pose would wall off a task object from the robot"]
    step = next(s for s in steps if s.why)
    chosen = np.flatnonzero((step.candidates == [step.x, step.z, step.rotation]).all(axis=1))
    assert len(chosen) == 1 and step.scores[chosen[0]] < step.scores.max()  # not its lowest-energy pose


def test_an_object_left_out_is_placed_after_the_objects_in_its_way_are_placed_again():
    plan = _plan("dense-00389", "dense")  # greedy finds no room for one object of this crowded bedroom
    ep = finished(plan)
    left_out = set(ep.failed)
    before = scene_metrics(plan, ep.layout("greedy", 0, 0.0))
    steps = []
    done = make_room(ep, steps.append)
    after = scene_metrics(plan, ep.layout("greedy", 0, 0.0))
    assert len(left_out) == 1 and done[0] in left_out and not ep.failed and [s.object_id for s in steps] == done
    assert after.cnt == 1.0 > before.cnt and after.collisions == 0 and after.oob == 0
    assert all("total" in s.terms for s in steps)
    movers = [s.object_id for s in steps[1:]]
    assert steps[0].why == f"left out at first: room made by moving {', '.join(movers)}"
    assert all(s.why == f"making way for {steps[0].object_id}" for s in steps[1:])
    # the objects it moved may not be fixed ones: with them fixed, nothing moves and the object stays out
    fixed = {p.id: (p.x, p.z, p.rotation) for p in finished(plan).placed}
    again = finished(plan, fixed)
    assert make_room(again) == [] and set(again.failed) == left_out


def test_a_blocker_far_from_the_walled_off_object_is_the_one_moved():
    """A shelf standing across the room walls off the fridge by the west wall; the stools around the fridge
    are nearer to it but block nothing: the shelf is the object moved, and the fridge is reached again."""
    from models.placement.polish import Standing
    from models.placement.repair import _suspects
    from models.values import ConstraintPlan
    objects = [("fridge-0", "Fridge", 0.7, 0.7, "inference", (0.45, 1.5, 90.0)),
               ("shelvingunit-0", "ShelvingUnit", 2.9, 0.3, "context", (2.3, 1.5, 90.0))] + \
        [(f"stool-{k}", "Stool", 0.35, 0.35, "context", pose)
         for k, pose in enumerate([(0.3, 0.3, 0.0), (0.3, 2.7, 0.0), (1.0, 0.3, 0.0), (1.0, 2.7, 0.0)])]
    plan = ConstraintPlan.model_validate({
        "id": "walled", "constraints": "", "room": {"type": "kitchen", "width": 4.0, "depth": 3.0, "doors": [
            {"wall": "east", "center": 1.5, "width": 0.9}]},
        "objects": [{"id": i, "type": t, "size": {"x": w, "y": 1, "z": d}, "role": r} for i, t, w, d, r, _ in objects]})
    ep = finished(plan, {i: pose for i, *_, pose in objects})
    ep.problem.fixed = {"fridge-0": ep.problem.fixed["fridge-0"]}  # the others are the placer's to move
    assert ep.reach.unreachable(ep.placed) == ["fridge-0"]
    free = [p for p in ep.placed if p.id != "fridge-0"]
    assert _suspects(ep, Standing(ep), ["fridge-0"], free)[0] == "shelvingunit-0"
    assert restore_access(ep) == ["shelvingunit-0"] and not ep.reach.unreachable(ep.placed)
