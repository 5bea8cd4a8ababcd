"""Plan2Place: the network's shapes, the losses, a resumable seeded training run, and the solver's steps."""

import csv
import hashlib
import json
from pathlib import Path

import numpy as np
import pytest

torch = pytest.importorskip("torch")

from models.datasets import load_dataset  # noqa: E402
from models.datasets.varied import varied_plan  # noqa: E402
from models.metrics import scene_metrics  # noqa: E402
from models.placement import PlacementProblem, get_solver  # noqa: E402
from models.placement.greedy import Episode  # noqa: E402
from models.placement.plan2place.agent import (  # noqa: E402
    W_AUX, TrainConfig, export_weights, losses, plot_curves, rollout, start_from, train)
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
    _, trace = rollout(net, _plan(), np.random.default_rng(0))
    with_aux, without = losses(trace, True), losses(trace, False)
    assert without["aux_loss"] == 0
    expected = with_aux["policy_loss"] + 0.5 * with_aux["value_loss"] + W_AUX * with_aux["aux_loss"] \
        - 0.01 * with_aux["entropy"]
    assert torch.isclose(with_aux["loss"], expected)
    with_aux["loss"].backward()
    assert all(p.grad is not None for p in net.actor.parameters())



def test_a_forked_episode_leaves_the_original_as_it_was():
    ep = Episode(_plan(3))
    ep.apply(ep.options(), 0)
    placed, energy, i = list(ep.placed), ep.energy, ep.i
    twin = ep.fork()
    final = twin.finish_greedily()
    assert twin.done and len(twin.placed) > len(placed) and final == twin.energy
    assert ep.placed == placed and ep.energy == energy and ep.i == i and not ep.done


def test_teacher_judges_candidates_by_greedy_completion():
    """The greedy pick judged at the first step finishes exactly as a greedy episode from scratch; the
    teacher's policy loss weights the judged candidates' log-probabilities by their advantages."""
    plan = _plan(3)
    ep = Episode(plan)
    opts = ep.options()
    greedy_pick = int(np.argmin(opts.terms["total"]))
    assert ep.judge(opts, [greedy_pick])[0] == pytest.approx(Episode(plan).finish_greedily())
    torch.manual_seed(0)
    net = Plan2PlaceNet(NetConfig(hidden=16))
    _, trace = rollout(net, plan, np.random.default_rng(0), teacher=3)
    assert trace and all("judged" in t for t in trace)
    for logp, adv in (t["judged"] for t in trace):
        assert len(logp) == len(adv) in (3, 4) and abs(float(adv.sum())) < 1e-5  # advantages about their mean
    out = losses(trace, True)
    expected = -torch.stack([(lp * a).sum() for lp, a in (t["judged"] for t in trace)]).mean()
    assert torch.isclose(out["policy_loss"], expected)
    out["loss"].backward()
    assert all(p.grad is not None for p in net.actor.parameters())
    best = [t["best"] for t in trace]  # the imitation term: the log-probability of the best judged candidate
    assert all(torch.isclose(t["judged"][0], t["best"]).any() for t in trace)
    imitating = losses(trace, True, imitate=0.5)
    assert torch.isclose(imitating["policy_loss"], expected - 0.5 * torch.stack(best).mean())


def test_guarded_training_never_samples_a_pose_that_walls_off_a_task_object(monkeypatch):
    """`--guard`: the candidates the solver's reach guard would refuse are masked out of the sampled policy
    (zero probability, never judged by the teacher); `Episode.keeping` is the guard's test for each."""
    plan = next(r.plan for r in load_dataset("seen") if r.plan.id == "seen-00395")  # greedy walls one off
    ep, rng = Episode(plan), np.random.default_rng(0)
    refused = 0
    while not ep.done:  # greedy's episode, as `GreedySolver(guard=False)` places it
        opts = ep.options()
        order = np.argsort(opts.terms["total"] + rng.uniform(0, 1e-9, len(opts.feasible)), kind="stable")
        keeps = ep.keeping(opts, order)
        assert ep.guarded(opts, order) == order[int(np.argmax(keeps)) if keeps.any() else 0]
        refused += int(not keeps[0])
        ep.apply(opts, int(order[0]))
    assert refused  # the greedy pick walls a task object off at some step
    torch.manual_seed(0)
    net = Plan2PlaceNet(NetConfig(hidden=16))
    steps = []  # per guarded step: (did any candidate keep reach, task objects out of reach before, after)
    keeping, apply = Episode.keeping, Episode.apply

    def keeping_spy(ep, *args):
        keeps = keeping(ep, *args)
        steps.append((bool(keeps.any()), len(ep.reach.unreachable(ep.placed)), ep))
        return keeps

    def apply_spy(ep, *args):  # the rollout's own episode, not the teacher's forks
        reward = apply(ep, *args)
        if steps and steps[-1][-1] is ep:
            steps[-1] = (*steps[-1][:2], len(ep.reach.unreachable(ep.placed)))
        return reward

    monkeypatch.setattr(Episode, "keeping", keeping_spy)
    monkeypatch.setattr(Episode, "apply", apply_spy)
    for seed in range(6):
        steps.clear()
        _, trace = rollout(net, plan, np.random.default_rng(seed), teacher=2, guard=True)
        assert all(torch.isfinite(t["judged"][0]).all() for t in trace)  # no refused pose judged
        assert len(steps) == len(trace) and all(after <= before for ok, before, after in steps if ok)
    assert any(not ok for ok, *_ in steps)  # the case the mask leaves alone: every candidate walls one off
    out = losses(trace, True, imitate=1.0)
    assert torch.isfinite(out["loss"])
    out["loss"].backward()


def test_training_starts_from_exported_weights_of_the_same_network_only(tmp_path):
    cfg = TrainConfig(episodes=2, batch=2, checkpoint_every=2, net=NetConfig(hidden=16).as_dict())
    export_weights(train(cfg, tmp_path / "a", progress=False), tmp_path / "a.npz")
    net = Plan2PlaceNet(NetConfig(hidden=16))
    start_from(net, tmp_path / "a.npz")
    trained = torch.load(tmp_path / "a" / "checkpoint.pt", weights_only=False)["net"]
    assert all(torch.allclose(v, trained[k].half().float()) for k, v in net.state_dict().items())
    with pytest.raises(ValueError, match="network configuration"):
        start_from(Plan2PlaceNet(NetConfig(hidden=32)), tmp_path / "a.npz")
    softer = Plan2PlaceNet(NetConfig(hidden=16, prior_temp=0.2))  # the energy prior's scale is not a weight
    start_from(softer, tmp_path / "a.npz")
    assert all(torch.equal(v, net.state_dict()[k]) for k, v in softer.state_dict().items())


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


def test_the_repair_reward_makes_the_return_minus_the_energy_the_bench_judges():
    from models.energy.exact import layout_energy
    from models.placement.plan2place.agent import repaired_energy, untrained_network
    net, changed = untrained_network(), 0
    for rank in range(0, 40, 4):
        plan = _plan(rank)
        ep, trace = rollout(net, plan, np.random.default_rng(rank))
        placed = ep.energy
        assert sum(t["reward"] for t in trace) == pytest.approx(-placed, abs=1e-9)
        after = repaired_energy(ep)
        trace[-1]["reward"] += placed - after
        judged = layout_energy(plan, ep.layout("x", 0, 0.0).placements, ep.problem).total
        assert after == pytest.approx(judged, abs=1e-9)
        assert sum(t["reward"] for t in trace) == pytest.approx(-judged, abs=1e-9)
        changed += abs(after - placed) > 1e-6
    assert changed  # the repairs moved something on some plan: the reward is not the placed layout's


def test_training_on_varied_rooms_replans_the_episode_it_resumes_at(tmp_path):
    cfg = TrainConfig(episodes=3, batch=3, checkpoint_every=3, net=NetConfig(hidden=16).as_dict(), dataset="varied")
    train(cfg, tmp_path / "a", progress=False)
    rows = list(csv.DictReader((tmp_path / "a" / "train.csv").open()))
    assert [r["plan"] for r in rows] == [varied_plan(0, e).id for e in range(3)]
    assert [int(r["objects"]) for r in rows] == [len(varied_plan(0, e).objects) for e in range(3)]


def test_solver_steps_are_the_policy_and_fixed_poses_are_kept():
    plan = _plan(40)
    steps = []
    solver = get_solver("plan2place")
    layout = solver.solve(plan, seed=0, observer=steps.append)
    m = scene_metrics(plan, layout, PlacementProblem.from_plan(plan))
    assert m.collisions == 0 and m.oob == 0 or layout.unplaced
    placing = len(PlacementProblem.from_plan(plan).order)  # one step per object, then the repairs' moves
    assert len(steps) >= placing and all(s.why for s in steps[placing:])
    assert {s.object_id for s in steps[:placing]} == {o.id for o in plan.objects}
    for s in steps[:placing]:
        if s.x is not None:
            finite = np.isfinite(s.scores)
            assert abs(s.scores[finite].sum() - 1) < 1e-4 and s.scores[finite].max() > 0
    moved = layout.placements[0]
    pose = (moved.x, moved.z, moved.rotation)
    again = solver.solve(plan, seed=0, fixed={moved.id: pose})
    assert next((p.x, p.z, p.rotation) for p in again.placements if p.id == moved.id) == pose
    assert get_solver("plan2place_untrained").solve(plan, seed=0).placements


# ---- speed work (issue 8, PTO): the fast paths decide exactly what the old code decided ---------------

KNOWN = Path(__file__).parent / "fixtures" / "plan2place_known_layouts.json"


def _placing_only(name: str):
    """The solver without the repairs and the reach guard, which came after the fixture (they have tests of
    their own)."""
    from models.placement.greedy import GreedySolver
    from models.placement.plan2place.agent import fast_policy, untrained_network
    from models.placement.plan2place.solver import Plan2PlaceSolver
    if name == "greedy":
        return GreedySolver(repair=False, guard=False)
    if name == "plan2place":
        return Plan2PlaceSolver(repair=False, guard=False)
    return Plan2PlaceSolver(fast_policy(untrained_network()), name=name, repair=False, guard=False)


def test_layouts_are_the_known_answer_of_the_code_before_the_speed_work():
    """Poses (and every step's immediate energy) of greedy, plan2place and plan2place_untrained on 10 `seen`
    plans x 2 seeds, recorded with the code before the speed work (commit 82c82be): the numpy network,
    the shared per-step cache and the incremental navigation grid must not change a decision. The
    plan2place entries are re-recorded for each new shipped network by `record_plan2place`, with the torch
    network's own forward pass (the numpy actor the solver runs must decide as it does)."""
    from app.bench.placement import pick_records
    known = json.loads(KNOWN.read_text())
    weights = hashlib.sha256((Path(__file__).parents[1] / "models/weights/plan2place/plan2place.npz").read_bytes())
    plans = {r.plan.id: r.plan for r in pick_records("seen", 20)}
    assert list(known["plans"]) == [pid for pid in plans][::2]
    for key, want in known["layouts"].items():
        name, seed, pid = key.split("/")
        if name == "plan2place":
            assert weights.hexdigest() == known["weights_sha256"], "new weights: python tests/test_plan2place.py"
        steps = []
        layout = _placing_only(name).solve(plans[pid], seed=int(seed), observer=steps.append)
        assert sorted([p.id, p.x, p.z, p.rotation] for p in layout.placements) == want["poses"], key
        assert sorted([u.id, u.reason] for u in layout.unplaced) == want["unplaced"], key
        assert [round(s.terms["total"], 9) if "total" in s.terms else None for s in steps] == want["step_totals"], key


def record_plan2place() -> None:
    """Re-record the fixture's plan2place entries with the shipped weights run by the torch network."""
    from app.bench.placement import pick_records
    from models.placement.plan2place.agent import network_of
    from models.placement.plan2place.policy import shipped_weights
    from models.placement.plan2place.solver import Plan2PlaceSolver
    known = json.loads(KNOWN.read_text())
    net = network_of(shipped_weights())
    solver = Plan2PlaceSolver(lambda obs: net.policy(obs).numpy(), use_global=net.use_global, repair=False,
                              guard=False)
    plans = {r.plan.id: r.plan for r in pick_records("seen", 20)}
    for key in [k for k in known["layouts"] if k.startswith("plan2place/")]:
        _, seed, pid = key.split("/")
        steps = []
        layout = solver.solve(plans[pid], seed=int(seed), observer=steps.append)
        known["layouts"][key] = {
            "poses": sorted([p.id, p.x, p.z, p.rotation] for p in layout.placements),
            "unplaced": sorted([u.id, u.reason] for u in layout.unplaced),
            "step_totals": [round(s.terms["total"], 9) if "total" in s.terms else None for s in steps]}
    weights = Path(__file__).parents[1] / "models/weights/plan2place/plan2place.npz"
    known["weights_sha256"] = hashlib.sha256(weights.read_bytes()).hexdigest()
    known["plan2place_recorded_with"] = "tests/test_plan2place.py record_plan2place (the torch forward pass)"
    head = {k: v for k, v in known.items() if k != "layouts"}
    lines = [f" {json.dumps(k)}: {json.dumps(v)}," for k, v in head.items()]
    rows = [f"  {json.dumps(k)}: {json.dumps(v, separators=(',', ':'))}" for k, v in known["layouts"].items()]
    KNOWN.write_text("{\n" + "\n".join(lines) + '\n "layouts": {\n' + ",\n".join(rows) + "\n }\n}\n")


def _observations(n_plans=4):
    from app.bench.placement import pick_records
    for r in pick_records("seen", n_plans):
        ep = Episode(r.plan)
        rng = np.random.default_rng(1)
        while not ep.done:
            opts = ep.options()
            if len(opts.feasible):
                subset = choose_subset(opts, rng)
                yield ep, opts, subset, observe(ep, opts, subset)
            ep.apply(opts, int(rng.integers(len(opts.feasible))) if len(opts.feasible) else None)


def test_policy_paths_equal_the_networks_forward():
    from models.placement.plan2place.agent import fast_policy, network_of
    from models.placement.plan2place.policy import shipped_weights
    net = network_of(shipped_weights())
    for _, _, _, obs in _observations():
        with torch.no_grad():
            logits, _ = net(obs, torch.zeros(8))
        assert torch.equal(net.policy(obs), logits)  # the SAGEConv arithmetic without its machinery: bit for bit
        fast = fast_policy(net)(obs)  # float32 numpy: other summation orders
        assert fast.dtype == np.float32 and np.abs(fast - logits.numpy()).max() < 1e-4
        assert int(np.argmax(fast)) == int(torch.argmax(logits))


def test_fast_policy_follows_weight_updates():
    from models.placement.plan2place.agent import fast_policy
    torch.manual_seed(0)
    net = Plan2PlaceNet(NetConfig(hidden=32))
    obs = next(_observations(1))[3]
    before = fast_policy(net)(obs)
    with torch.no_grad():
        net.actor[2].bias += 1.0  # an in-place update, as an optimiser step makes
    after = fast_policy(net)(obs)
    assert np.allclose(after, before + 1.0, atol=1e-5)


def _observe_reference(ep, opts, subset):
    """The per-object / per-edge loops `observe` had before it was vectorised (node and edge features), and the
    candidates' features one candidate at a time."""
    from models.placement.plan2place.features import EDGE_DIM, NODE_DIM
    from models.placement.plan2place.type_embedding import EMBED_DIM, embed
    room = ep.problem.plan.room
    W, D = room.width, room.depth
    cons = ep.problem.constraints.objects
    obj, objs = opts.obj, ep.order
    index = {o.id: k for k, o in enumerate(objs)}
    pose = {p.id: p for p in ep.placed}
    nodes = np.zeros((len(objs), NODE_DIM), np.float32)
    for k, o in enumerate(objs):
        p = pose.get(o.id)
        r = np.radians(p.rotation) if p else 0.0
        nodes[k, :10] = [o.size.x / W, o.size.z / D, p.x / W if p else 0, p.z / D if p else 0,
                         np.sin(r) if p else 0, np.cos(r) if p else 0, p is not None, o.id == obj.id, o.is_task,
                         ep.problem.clearance.get(o.id, 0.0)]
        nodes[k, 10:10 + EMBED_DIM] = embed(o.type)
    pairs = {(index[a], index[c.target]) for a, oc in cons.items() if a in index
             for c in oc.relations if c.target in index}
    pairs |= {(index[p.id], index[obj.id]) for p in ep.placed if p.id in index}
    pairs = sorted(pairs | {(b, a) for a, b in pairs})
    edges = np.array(pairs, np.int64).T.reshape(2, -1)
    if edges.shape[1]:
        feat = np.zeros((edges.shape[1], EDGE_DIM), np.float32)
        for e, (a, b) in enumerate(edges.T):
            pa, pb = pose.get(objs[a].id), pose.get(objs[b].id)
            constrained = any(c.target == objs[b].id for c in cons[objs[a].id].relations)
            if pa and pb:
                dx, dz = pb.x - pa.x, pb.z - pa.z
                dist = np.hypot(dx, dz)
                feat[e] = [dist / np.hypot(W, D), dx / (dist + 1e-6), dz / (dist + 1e-6),
                           abs(np.cos(np.radians(pa.rotation - pb.rotation))), constrained]
            else:
                feat[e, 4] = constrained
        sums = np.zeros((len(objs), EDGE_DIM), np.float32)
        np.add.at(sums, edges[1], feat)
        counts = np.bincount(edges[1], minlength=len(objs))[:, None]
        nodes[:, 10 + EMBED_DIM:] = sums / np.maximum(counts, 1)
    return nodes, edges, _candidates_reference(opts, subset, W, D)


def _candidates_reference(opts, subset, W, D):
    """The candidates' features, candidate by candidate, as the module docstring lists them."""
    from models.placement.plan2place.features import TERMS
    obj, total = opts.obj, opts.terms["total"][subset]
    rows = []
    for k, (x, z, rot) in zip(subset, opts.cands[opts.feasible[subset]]):
        w, d = (obj.size.x, obj.size.z) if rot % 180 == 0 else (obj.size.z, obj.size.x)
        wall = min(x - w / 2, z - d / 2, W - x - w / 2, D - z - d / 2)
        turn = [float(int(rot // 90) % 4 == j) for j in range(4)]
        rows.append([x / W, z / D, min(wall, 2.0) / 2, float(wall < 0.15), np.hypot(x - W / 2, z - D / 2) / np.hypot(W, D),
                     *turn, *(opts.terms[t][k] for t in TERMS), opts.terms["total"][k] - total.min(), opts.soft[k] / 10])
    return np.array(rows).astype(np.float32)


def test_vectorised_observation_equals_the_loops():
    for ep, opts, subset, obs in _observations():
        nodes, edges, cands = _observe_reference(ep, opts, subset)
        assert np.array_equal(obs.nodes, nodes) and np.array_equal(obs.edges, edges) and obs.edges.dtype == np.int64
        assert obs.cands.dtype == np.float32 and np.array_equal(obs.cands, cands)


def test_train_placement_command_at_tiny_scale_with_the_repair_reward(tmp_path):
    from app.cli import main
    args = ["train", "placement", "--out", str(tmp_path), "--episodes", "2", "--batch", "2", "--hidden", "16",
            "--guard", "--repair-reward"]
    assert main(args) == 0
    assert json.loads((tmp_path / "config.json").read_text())["repair_reward"] is True
    rows = list(csv.DictReader((tmp_path / "train.csv").open()))
    assert len(rows) == 2 and all(float(r["return"]) == pytest.approx(-float(r["total"]), abs=1e-4) for r in rows)
    assert (tmp_path / "curves.png").stat().st_size > 1000 and (tmp_path / "plan2place.npz").exists()
    with pytest.raises(ValueError, match="another configuration"):  # resuming asks for the same options
        main([*args[:-1], "--episodes", "3"])


if __name__ == "__main__":
    record_plan2place()
