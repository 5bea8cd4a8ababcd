"""Going back when an object finds no room (models.placement.backtrack): the steps then place an object they left out,
with no collision and no more task objects out of reach, and show the steps done again with their reason; a try that
raises the step energy or cuts a task object off is refused; where nothing is left out, the steps are those of a
placer that commits each pose for good."""

import numpy as np
import pytest

from models.datasets import load_dataset
from models.placement import backtrack
from models.placement.backtrack import AGAIN, _better
from models.placement.greedy import Episode, GreedySolver, place_stepwise
from models.placement.plan2place.policy import place, shipped_policy, shipped_weights
from episode_support import judged

PLANS = {r.plan.id: r.plan for r in load_dataset("dense")}
ROOM = "dense-00597"  # the steps leave two of its ten objects out; going back places both


def steps(plan, depth: int, observer=None, seed: int = 0):
    """Plan2Place's steps on `plan`, no repairs, going back at most `depth` steps."""
    shipped = backtrack.DEPTH
    backtrack.DEPTH = depth
    try:
        return place(shipped_policy(), plan, np.random.default_rng(seed), shipped_weights().use_global, None, observer,
                     repair=False)
    finally:
        backtrack.DEPTH = shipped


def test_going_back_places_an_object_the_steps_left_out_without_collision_or_cutting_a_task_object_off():
    plan, records = PLANS[ROOM], []
    without, went_back = steps(plan, 0), steps(plan, backtrack.DEPTH, records.append)
    assert without.failed and len(went_back.failed) < len(without.failed)
    before, _, out_before = judged(plan, without)
    after, _, out_after = judged(plan, went_back)
    assert after.collisions == 0 and after.oob == 0 and after.cnt > before.cnt
    assert out_after + sum(o in went_back.reach.task for o in went_back.failed) <= \
        out_before + sum(o in without.reach.task for o in without.failed)
    # the steps done again say why, and each object ends where its last step put it
    again = [r for r in records if r.why.startswith(AGAIN.format(""))]
    made_room_for = {r.why.split("; ")[0].removeprefix(AGAIN.format("")) for r in again}
    assert again and made_room_for <= set(without.failed) and not made_room_for & set(went_back.failed)
    last = {r.object_id: (r.x, r.z, r.rotation) for r in records}
    assert all(last[p.id] == (p.x, p.z, p.rotation) for p in went_back.placed)


def test_a_try_with_a_higher_step_energy_or_a_task_object_cut_off_is_refused():
    went_back = steps(PLANS[ROOM], backtrack.DEPTH)
    left_out = went_back.fork()  # the same layout, standing for the episode that left the object out
    left_out.energy = went_back.energy + 1.0
    assert _better(went_back, left_out)
    left_out.energy = went_back.energy
    assert not _better(went_back, left_out)  # the step energy is not lower
    left_out.energy = went_back.energy + 1.0
    cut_off = went_back.fork()
    task = next(p.id for p in went_back.placed if p.id in went_back.reach.task)
    cut_off.failed = {**cut_off.failed, task: "no room"}  # one more task object the robot cannot reach
    assert not _better(cut_off, left_out)


def committed(plan, choose, seed: int = 0) -> Episode:
    """The steps as a placer took them before it could go back: each object's pose chosen once, for good."""
    ep, rng = Episode(plan), np.random.default_rng(seed)
    while not ep.done:
        opts = ep.options()
        ep.apply(opts, choose(ep, opts, rng)[0] if len(opts.feasible) else None)
    return ep


@pytest.mark.parametrize("pid", [r.plan.id for r in load_dataset("seen", "validation")[:3]])
def test_where_no_object_is_left_out_the_steps_are_those_chosen_once_for_good(pid):
    plan = next(r.plan for r in load_dataset("seen", "validation") if r.plan.id == pid)
    choose = GreedySolver()._choose
    without = committed(plan, choose)
    went_back = place_stepwise(plan, np.random.default_rng(0), choose, repair=False)
    assert not without.failed
    assert [(p.id, p.x, p.z, p.rotation) for p in without.placed] == \
        [(p.id, p.x, p.z, p.rotation) for p in went_back.placed]
