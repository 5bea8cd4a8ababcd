"""The look-ahead placer: greedy's candidates judged by finishing the episode greedily. With one candidate per step
(or no time left) it is greedy; with more, each step takes the judged candidate that ends lowest, legally."""

import numpy as np
import pytest

from models.datasets import load_dataset
from models.metrics import scene_metrics
from models.placement import PlacementProblem, get_solver
from models.placement.greedy import Episode, GreedySolver
from models.placement.lookahead import LOOKAHEAD_K, LookaheadSolver

SEEN = sorted(load_dataset("seen", "validation"), key=lambda r: len(r.plan.objects))
DENSE = load_dataset("dense")


def _poses(layout):
    return {p.id: (p.x, p.z, p.rotation) for p in layout.placements}


@pytest.mark.parametrize("plan", [SEEN[40].plan, DENSE[3].plan], ids=["seen", "dense"])
def test_one_candidate_per_step_or_no_time_left_is_greedy(plan):
    greedy = _poses(GreedySolver(repair=False).solve(plan, seed=2))
    assert _poses(LookaheadSolver(k=1, repair=False).solve(plan, seed=2)) == greedy
    assert _poses(LookaheadSolver(repair=False).solve(plan, seed=2, time_budget_s=0.0)) == greedy


def test_each_step_takes_the_judged_candidate_that_ends_lowest():
    plan = SEEN[60].plan
    steps = []
    LookaheadSolver(repair=False).solve(plan, seed=0, observer=steps.append)
    ep = Episode(plan)
    opts = ep.options()
    order = np.argsort(opts.terms["total"] + np.random.default_rng(0).uniform(0, 1e-9, len(opts.feasible)),
                       kind="stable")
    judged = ep.first_kept(opts, order, LOOKAHEAD_K)
    finals = ep.judge(opts, judged)
    assert len(judged) == LOOKAHEAD_K
    best = opts.cands[opts.feasible[judged[int(np.argmin(finals))]]]
    assert (steps[0].x, steps[0].z, steps[0].rotation) == tuple(float(v) for v in best)
    assert abs(steps[0].scores[np.isfinite(steps[0].scores)].sum() - 1) < 1e-6  # the heat-map: judged ones only
    assert (steps[0].scores > 0).sum() <= LOOKAHEAD_K


def test_it_places_legally_and_reports_every_object():
    for record in (SEEN[10], SEEN[-1], DENSE[0]):
        plan = record.plan
        layout = get_solver("lookahead").solve(plan, seed=1)
        m = scene_metrics(plan, layout, PlacementProblem.from_plan(plan))
        assert m.collisions == 0 and m.oob == 0.0
        assert {p.id for p in layout.placements} | {u.id for u in layout.unplaced} == {o.id for o in plan.objects}
        assert all(u.reason for u in layout.unplaced)


def test_it_judges_at_least_one_candidate():
    with pytest.raises(ValueError, match="at least one candidate"):
        LookaheadSolver(k=0)
