"""The companions' pass: habits read from the training rooms' prior, moves only when the layout keeps more
of them at no constraint, energy or reach cost; never a fixed object, nothing in a crowded room."""

import numpy as np

from models.datasets import load_dataset
from models.energy.prior import relation_prior
from models.placement import habits
from models.placement.habits import Habits, keep_companions
from episode_support import judged, polished

PLANS = [r.plan for r in load_dataset("seen", "train")[:80]]


def test_habits_come_from_the_training_rooms_prior():
    prior = relation_prior()
    assert prior.companion_gap("kitchen", "Chair", "DiningTable") == 0.1  # chairs stand at the table
    assert prior.companion_gap("bedroom", "SideTable", "Bed") == 0.3
    assert prior.companion_gap("kitchen", "Fridge", "Toilet") is None  # never seen together
    assert prior.companion_gap("bedroom", "Bed", "Desk") is None  # seen together, not kept near


def test_on_many_plans_a_move_keeps_more_habits_and_costs_nothing():
    moved_plans = 0
    for plan in PLANS:
        ep = polished(plan)
        before, energy, out = judged(plan, ep)
        kept_before = Habits(plan, ep.placed).kept()
        steps = []
        moved = keep_companions(ep, steps.append)
        assert [s.object_id for s in steps] == moved, plan.id
        for s in steps:  # the reason the studio shows names a companion type of the plan now near
            named = s.why.removeprefix("standing by its ").removesuffix(", as in the iTHOR rooms").split(", ")
            assert named[0] and set(named) <= {o.type for o in plan.objects}, s.why
        if not moved:
            continue
        moved_plans += 1
        after, new_energy, new_out = judged(plan, ep)
        assert Habits(plan, ep.placed).kept() > kept_before, plan.id
        assert after.constraint_satisfaction >= before.constraint_satisfaction, plan.id
        assert new_energy <= energy + 1e-9 and new_out <= out, plan.id
        assert after.collisions == 0 and after.oob == 0 and after.cnt == before.cnt, plan.id
    assert moved_plans >= 5  # the claim is tested on real moves, not on layouts left alone


def test_fixed_objects_never_move_and_a_crowded_room_is_left_alone(monkeypatch):
    plan = next(p for p in PLANS if keep_companions(polished(p)))
    fixed = {p.id: (p.x, p.z, p.rotation) for p in polished(plan).placed}
    assert keep_companions(polished(plan, fixed)) == []
    dense = polished(load_dataset("dense")[0].plan)

    def not_asked(plan):
        raise AssertionError("a crowded room's habits were looked up")
    monkeypatch.setattr(habits, "companions", not_asked)
    assert keep_companions(dense) == []


def test_the_habits_kept_after_a_move_are_counted_again_only_where_the_move_can_change_them():
    """`kept_with` (the companions' pass's test of a pose) equals `kept` of the whole moved layout."""
    rng, checked, changed = np.random.default_rng(0), 0, 0
    for plan in PLANS[:20]:
        ep = polished(plan)
        h = Habits(plan, ep.placed)
        now = h.kept()
        for p in ep.placed:
            cands, body = ep.scorer.bodies(plan.object(p.id))
            for i in rng.choice(len(cands), size=min(5, len(cands)), replace=False):
                whole = h.kept({**h.feet, p.id: body[i]})
                assert h.kept_with(p.id, body[i], now) == whole, (plan.id, p.id)
                checked, changed = checked + 1, changed + (whole != now)
    assert checked > 500 and changed > 20  # moves that gain and lose habits, not only neutral ones
