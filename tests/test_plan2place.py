"""Plan2Place: the network's shapes, the losses, a resumable seeded training run, and the solver's steps."""

import csv

import numpy as np
import pytest

torch = pytest.importorskip("torch")

from models.datasets import load_dataset  # noqa: E402
from models.metrics import scene_metrics  # noqa: E402
from models.placement import PlacementProblem, get_solver  # noqa: E402
from models.placement.greedy import Episode  # noqa: E402
from models.placement.plan2place.agent import W_AUX, TrainConfig, losses, plot_curves, rollout, train  # noqa: E402
from models.placement.plan2place.features import CAND_DIM, choose_subset, observe  # noqa: E402
from models.placement.plan2place.network import NetConfig, Plan2PlaceNet  # noqa: E402


def _plan(rank=0):
    recs = sorted(load_dataset("seen", "validation"), key=lambda r: len(r.plan.objects))
    return recs[rank].plan


@pytest.mark.parametrize("fusion", ["cross", "self", "concat"])
def test_network_scores_every_candidate(fusion):
    ep = Episode(_plan())
    opts = ep.options()
    subset = choose_subset(opts, np.random.default_rng(0))
    obs = observe(ep, opts, subset)
    net = Plan2PlaceNet(NetConfig(hidden=32, fusion=fusion))
    logits, value = net(obs, torch.zeros(8))
    assert obs.cands.shape == (len(subset), CAND_DIM) and logits.shape == (len(subset),) and value.dim() == 0


def test_losses_weights_and_gradients():
    torch.manual_seed(0)
    net = Plan2PlaceNet(NetConfig(hidden=32))
    _, trace = rollout(net, _plan(), np.random.default_rng(0), sample=True, grad=True)
    with_aux, without = losses(trace, True), losses(trace, False)
    assert without["aux_loss"] == 0
    expected = with_aux["policy_loss"] + 0.5 * with_aux["value_loss"] + W_AUX * with_aux["aux_loss"] \
        - 0.01 * with_aux["entropy"]
    assert torch.isclose(with_aux["loss"], expected)
    with_aux["loss"].backward()
    assert all(p.grad is not None for p in net.actor.parameters())


def test_training_is_seeded_and_resumes(tmp_path):
    cfg = TrainConfig(episodes=4, batch=2, checkpoint_every=2, net=NetConfig(hidden=16).as_dict())
    train(cfg, tmp_path / "a", progress=False)
    cfg2 = TrainConfig(episodes=2, batch=2, checkpoint_every=2, net=NetConfig(hidden=16).as_dict())
    train(cfg2, tmp_path / "b", progress=False)
    train(cfg, tmp_path / "b", progress=False)  # resumed from episode 2 up to 4
    a = list(csv.DictReader((tmp_path / "a" / "train.csv").open()))
    b = list(csv.DictReader((tmp_path / "b" / "train.csv").open()))
    assert [r["plan"] for r in a] == [r["plan"] for r in b]
    assert [r["return"] for r in a] == [r["return"] for r in b]
    assert plot_curves({"x": tmp_path / "a" / "train.csv"}, tmp_path / "c.png").stat().st_size > 1000


def test_solver_steps_are_the_policy_and_fixed_poses_are_kept():
    plan = _plan(40)
    steps = []
    solver = get_solver("plan2place")
    layout = solver.solve(plan, seed=0, observer=steps.append)
    m = scene_metrics(plan, layout, PlacementProblem.from_plan(plan))
    assert m.collisions == 0 and m.oob == 0 or layout.unplaced
    assert len(steps) == len(PlacementProblem.from_plan(plan).order)
    for s in steps:
        if s.x is not None:
            finite = np.isfinite(s.scores)
            assert abs(s.scores[finite].sum() - 1) < 1e-4 and s.scores[finite].max() > 0
    moved = layout.placements[0]
    pose = (moved.x, moved.z, moved.rotation)
    again = solver.solve(plan, seed=0, fixed={moved.id: pose})
    assert next((p.x, p.z, p.rotation) for p in again.placements if p.id == moved.id) == pose
    assert get_solver("plan2place_untrained").solve(plan, seed=0).placements
