"""Solving again from another random state where objects are left out (models.placement.restarts): in crowded iTHOR
rooms the object a seed's episode leaves out is placed by a sampled one, at a lower energy, its steps shown after the
first's; a kept solve never places fewer, reaches fewer or ends higher by the exact judge; where nothing is left out
nothing runs; the drawn poses keep the reach guard; a seed gives one layout."""

import numpy as np
import pytest

from models.datasets import load_dataset
from models.placement import restarts
from models.placement.greedy import Episode
from models.placement.plan2place.policy import place, shipped_policy, shipped_weights
from models.placement.reach_kept import WALLS
from models.placement.restarts import AGAIN, better, drawn, restarted
from models.placement.result import NO_ROOM
from episode_support import judged

pytestmark = pytest.mark.usefixtures("no_exact_finish")  # each pass alone

HUMAN = {r.plan.id: r.plan for r in load_dataset("human")}
DENSE = {r.plan.id: r.plan for r in load_dataset("dense")}
KITCHEN, BEDROOM = "human-FloorPlan27", "human-FloorPlan316"  # the 2.9 m counter; the chair beside a 2.5 m desk


def solved(plan, seed: int, observer=None) -> Episode:
    """Plan2Place's episode with every repair but the exact finish."""
    return place(shipped_policy(), plan, np.random.default_rng(seed), shipped_weights().use_global, None, observer)


def without_restarts(plan, seed: int, monkeypatch) -> Episode:
    with monkeypatch.context() as m:
        m.setattr(restarts, "RESTARTS", 0)
        return solved(plan, seed)


@pytest.mark.parametrize("pid, seed, left_out", [(KITCHEN, 1, {"countertop-0": WALLS}),
                                                 (BEDROOM, 4, {"chair-0": NO_ROOM})])
def test_the_object_a_seed_leaves_out_is_placed_by_a_solve_from_another_state(pid, seed, left_out, monkeypatch):
    plan, records = HUMAN[pid], []
    first = without_restarts(plan, seed, monkeypatch)
    kept = solved(plan, seed, records.append)
    assert first.failed == left_out
    before, energy, out = judged(plan, first)
    after, new_energy, new_out = judged(plan, kept)
    assert not kept.failed and after.cnt == 1 > before.cnt and new_out == out == 0
    assert new_energy < energy and after.collisions == 0 and after.oob == 0
    # the first episode's steps, then the kept one's, each saying why, from an empty room
    start = next(k for k, r in enumerate(records) if r.why.startswith(AGAIN))
    assert records[start].restart and all(r.why.startswith(AGAIN) for r in records[start:])
    last = {r.object_id: (r.x, r.z, r.rotation) for r in records}
    assert all(last[p.id] == (p.x, p.z, p.rotation) for p in kept.placed)


@pytest.mark.parametrize("pid", ["dense-00388", "dense-01172", "dense-01519", "dense-01643"])
def test_a_kept_solve_places_no_fewer_reaches_no_fewer_and_ends_no_higher_by_the_exact_judge(pid, monkeypatch):
    plan, changed = DENSE[pid], 0
    for seed in range(2):
        first, kept = without_restarts(plan, seed, monkeypatch), solved(plan, seed)
        (before, energy, out), (after, new_energy, new_out) = judged(plan, first), judged(plan, kept)
        assert after.cnt >= before.cnt and new_out <= out and new_energy <= energy + 1e-9
        if kept.layout("p", 0, 0.0) != first.layout("p", 0, 0.0):
            changed += 1
            assert better(kept, first) and new_energy < energy
    assert changed  # a solve from another state was kept in one seed at least


def test_a_solve_that_places_fewer_or_ends_no_lower_is_not_kept(monkeypatch):
    plan = HUMAN[KITCHEN]
    first, kept = without_restarts(plan, 1, monkeypatch), solved(plan, 1)
    assert better(kept, first) and not better(first, kept) and not better(kept, kept)
    seen = []
    assert restarted(first, lambda salt, observer: seen.append(salt) or first) is first
    assert seen == list(range(1, restarts.RESTARTS + 1))  # each try, as the first stays left out


@pytest.mark.parametrize("pid", [r.plan.id for r in load_dataset("seen", "validation")[:3]])
def test_where_nothing_is_left_out_nothing_is_solved_again(pid, monkeypatch):
    plan = next(r.plan for r in load_dataset("seen", "validation") if r.plan.id == pid)
    salts = []
    monkeypatch.setattr(restarts, "salted", lambda rng, salt: salts.append(salt) or rng)
    records = []
    ep = solved(plan, 0, records.append)
    assert not ep.failed and not salts and not any(r.why.startswith(AGAIN) for r in records)


def test_a_drawn_pose_never_cuts_a_task_object_off_where_the_pick_did_not():
    """A placer whose probabilities favour the poses that cut the task object off: each draw that would is replaced by
    the pick, which keeps the way open."""
    plan = DENSE["dense-00658"]

    def favour_cuts(ep, opts, rng):
        order = np.argsort(opts.terms["total"], kind="stable")
        keeps = ep.keeping(opts, order[:50])
        probs = np.full(len(opts.feasible), 1e-6)
        probs[order[:50][~keeps]] = 1.0
        return int(order[:50][keeps][0]) if keeps.any() else int(order[0]), probs / probs.sum(), ""

    ep, draw, rng, drawn_other = Episode(plan), drawn(favour_cuts), np.random.default_rng(0), 0
    while not ep.done:
        opts = ep.options()
        if not len(opts.feasible):
            ep.apply(opts, None)
            continue
        pick, cut = favour_cuts(ep, opts, rng)[0], len(ep.reach.unreachable(ep.placed))
        keeps = bool(ep.keeping(opts, np.array([pick]))[0])
        k = draw(ep, opts, rng)[0]
        drawn_other += k != pick
        ep.apply(opts, k)
        assert not keeps or len(ep.reach.unreachable(ep.placed)) <= cut
    assert drawn_other  # poses other than the pick were drawn


def test_the_restarts_share_the_first_solves_plan_only_parts(monkeypatch):
    """Every solve of a plan, restarts included, reads the plan once and makes its candidates' geometry once."""
    from models.placement import candidates
    made, init = [], candidates.CandidateScorer.__init__

    def counting(self, problem, step=None, like=None):
        made.append(like is None)
        init(self, problem, step, like)

    monkeypatch.setattr(candidates.CandidateScorer, "__init__", counting)
    records = []
    solved(HUMAN[KITCHEN], 1, records.append)
    assert any(r.restart for r in records)  # a restart ran
    assert sum(made) == 1 and len(made) > 2


def test_a_seed_gives_one_layout():
    plan = HUMAN[BEDROOM]
    assert solved(plan, 4).layout("p", 4, 0.0) == solved(plan, 4).layout("p", 4, 0.0)
