"""Solving again with the objects left out placed first (models.placement.again): the objects named first come
right after the fixed ones; a kept episode places more objects without reaching fewer task objects, or reaches
more with as many, and its steps say why; where nothing is left out nothing is solved again."""

import numpy as np
import pytest

from models.datasets import load_dataset
from models.placement import again
from models.placement.again import AGAIN, reached
from models.placement.greedy import Episode, GreedySolver, place_stepwise, tie_broken
from models.placement.problem import PlacementProblem


def _greedy(ep, opts, rng):
    total = tie_broken(opts, rng)
    return int(np.argmin(total)), np.ones(len(total)) / len(total), ""


@pytest.fixture(scope="module")
def dense():
    return [r.plan for r in load_dataset("dense")[:24]]


def test_the_objects_named_first_come_right_after_the_fixed_ones(dense):
    plan = dense[0]
    usual = [o.id for o in PlacementProblem.from_plan(plan).order]
    first = [usual[-1], usual[-3]]
    fixed = {usual[2]: (1.0, 1.0, 0.0)}
    order = [o.id for o in PlacementProblem.from_plan(plan, fixed, first).order]
    assert order[0] == usual[2] and order[1:3] == [usual[-3], usual[-1]]  # in the usual order among themselves
    assert [i for i in order if i not in first and i not in fixed] == [i for i in usual if i not in first and i not in fixed]
    assert [o.id for o in Episode(plan, fixed, first).order] == order


def test_a_kept_episode_places_more_or_reaches_more_and_its_steps_say_why(dense, monkeypatch):
    gains, shipped = 0, again.ROUNDS
    for plan in dense:
        monkeypatch.setattr(again, "ROUNDS", 0)
        once = place_stepwise(plan, np.random.default_rng(0), _greedy)
        monkeypatch.setattr(again, "ROUNDS", shipped)
        steps = []
        ep = place_stepwise(plan, np.random.default_rng(0), _greedy, observer=steps.append)
        before, after = (len(once.placed), reached(once)), (len(ep.placed), reached(ep))
        assert after[0] >= before[0] and after[1] >= before[1]  # never fewer objects placed or task objects reached
        if after != before:
            gains += 1
            said = [s.why for s in steps if s.why.startswith(AGAIN.split("{}")[0])]
            assert said and all(w.endswith(AGAIN.split("{}")[1]) for w in said)
            last = {s.object_id: (s.x, s.z, s.rotation) for s in steps}
            assert all(last[p.id] == (p.x, p.z, p.rotation) for p in ep.placed)  # the studio ends on the layout
        else:
            assert [(p.id, p.x, p.z, p.rotation) for p in ep.placed] == \
                [(p.id, p.x, p.z, p.rotation) for p in once.placed]
    assert gains >= 2  # it does something in these crowded rooms (checked: fails with ROUNDS 0)


def test_nothing_is_solved_again_where_nothing_is_left_out(monkeypatch):
    plan = next(r.plan for r in load_dataset("seen") if r.plan.id == "seen-00346")
    calls = []
    monkeypatch.setattr(again, "reached", lambda ep: calls.append(ep) or 0)
    layout = GreedySolver().solve(plan, seed=0)
    assert not layout.unplaced and calls == []
