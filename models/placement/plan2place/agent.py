"""Rollouts and actor-critic training of Plan2Place (paper, Supp.: losses weighted 1 / 0.5 / 0.1 / 0.01,
Adam, gamma 0.99). Seeded, resumable from `checkpoint.pt` in the run directory, CSV log per episode.

Reward per step: the drop of the vectorised energy (objects still to come pending, so the episode's
return is minus the final layout's energy, E_missing included). With `teacher` > 0 (not in the paper)
the policy loss takes its advantages from greedy completions instead of the sampled return: at each step
the `teacher` candidates of lowest immediate energy and the sampled one are each placed and the episode
finished greedily; a candidate's advantage is the judged candidates' mean final energy minus its own. With
`imitate` > 0 (not in the paper either) the policy loss also takes the cross-entropy towards the judged
candidate of lowest final energy: the policy is distilled from a one-step look-ahead over greedy
completions, which it must then replace at a fraction of its cost. With `repair_reward` (not in the paper) the
repairs run on each finished episode, as the solver's layouts are judged, and the last step's reward takes
their change of the exact energy: the return is minus the energy after the repairs. The auxiliary loss aligns the critic with
the semantic score as the paper does; the score (in [0, 1]) is shifted by -1 onto the return's scale
(0 for a layout the scorer finds human-like, -1 for one it does not).
"""

from __future__ import annotations

import csv
import json
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from functools import partial
from pathlib import Path

import numpy as np
import torch

from models.datasets.varied import NAME as VARIED, varied_plan
from models.placement.greedy import Episode
from models.placement.plan2place.features import choose_subset, observe
from models.placement.plan2place.network import Plan2PlaceNet
from models.placement.plan2place.policy import NetConfig, NumpyPolicy, Policy, Weights
from models.semantic import default_scorer, items_of
from models.values import ConstraintPlan

W_POLICY, W_VALUE, W_AUX, W_ENTROPY = 1.0, 0.5, 0.1, 0.01
GAMMA = 0.99
LOG_FIELDS = ("episode", "plan", "objects", "return", "rel", "collision", "oob", "nav", "aff", "missing", "total",
              "policy_loss", "value_loss", "aux_loss", "entropy", "seconds")


@dataclass
class TrainConfig:
    episodes: int = 2000
    batch: int = 4
    lr: float = 3e-4
    seed: int = 0
    use_global: bool = True
    aux: bool = True
    net: dict = field(default_factory=lambda: NetConfig().as_dict())
    dataset: str = "seen"  # a stored set's training split, or "varied" (models.datasets.varied)
    checkpoint_every: int = 20
    teacher: int = 0  # candidates per step judged by a greedy completion (0: advantages from the return)
    imitate: float = 0.0  # weight of the cross-entropy towards the teacher's best judged candidate
    init: str = ""  # start from these weights (an exported plan2place.npz) instead of random ones
    guard: bool = False  # sample with the reach guard as an action mask, as the solver places (not in the paper)
    repair_reward: bool = False  # the return after the repairs (models.placement.repair; not in the paper)


def semantic_of(ep: Episode) -> tuple[torch.Tensor, float]:
    room = ep.problem.plan.room
    types = {o.id: o.type for o in ep.problem.plan.objects}
    s = default_scorer().score(room.type, room.width, room.depth, items_of(ep.placed, types))
    return torch.from_numpy(s.features), s.score


def rollout(net: Plan2PlaceNet, plan, rng: np.random.Generator, use_global: bool = True,
            teacher: int = 0, guard: bool = False) -> tuple[Episode, list[dict]]:
    """One training episode: actions drawn from the policy, with gradients (the solver's deterministic
    episode, without torch, is `policy.place`). With `guard`, the candidates that would wall off a task
    object are masked out of the policy (unless all would: the solver's guard then takes the most wanted)."""
    ep = Episode(plan)
    trace = []
    while not ep.done:
        opts = ep.options()
        pick = None
        if len(opts.feasible):
            subset = choose_subset(opts, rng)
            obs = observe(ep, opts, subset, use_global)
            sem, r_vlm = semantic_of(ep)
            logits, value = net(obs, sem)
            allowed = np.ones(len(subset), bool)
            if guard and (keeps := ep.keeping(opts, subset)).any():
                allowed = keeps
                logits = logits.masked_fill(torch.from_numpy(~keeps), float("-inf"))
            dist = torch.distributions.Categorical(logits=logits)
            a = int(dist.sample())
            trace.append({"logp": dist.log_prob(torch.tensor(a)), "entropy": dist.entropy(), "value": value,
                          "r_vlm": r_vlm, "reward": 0.0})
            if teacher:  # the subset is sorted by immediate energy: its first `teacher` and the sampled one
                judged = sorted(set(np.flatnonzero(allowed)[:teacher].tolist()) | {a})
                finals = ep.judge(opts, subset[judged])
                trace[-1]["judged"] = (dist.log_prob(torch.tensor(judged)),
                                       torch.from_numpy(finals.mean() - finals).float())
                trace[-1]["best"] = dist.log_prob(torch.tensor(judged[int(np.argmin(finals))]))
            pick = int(subset[a])
        reward = ep.apply(opts, pick)
        if trace:  # a failed step after a decision: its energy change counts for that decision
            trace[-1]["reward"] += reward
    return ep, trace


def repaired_energy(ep: Episode) -> float:
    """Run the repairs on the finished episode `ep` (its layout and energy become the repaired ones) and return the
    exact energy of the result, as the bench judges a layout."""
    from models.energy.vectorised import CandidateEnergy
    from models.placement.repair import repair
    repair(ep)
    ep.terms = CandidateEnergy(ep.problem, ep.placed).terms()
    ep.energy = ep.terms["total"]
    return ep.energy


def fast_policy(net: Plan2PlaceNet) -> Policy:
    """obs -> logits (numpy) for inference: `NumpyPolicy` of the network's current weights (rebuilt when they
    change, e.g. by an optimiser step), or the torch actor for fusions it does not implement."""
    if net.cfg.fusion != "cross":
        return lambda obs: net.policy(obs).numpy()
    version = tuple(p._version for p in net.parameters())
    cached = getattr(net, "_numpy_policy", None)
    if cached is None or cached[0] != version:
        cached = (version, NumpyPolicy(arrays_of(net), net.cfg))
        net._numpy_policy = cached
    return cached[1]


def arrays_of(net: Plan2PlaceNet) -> dict[str, np.ndarray]:
    return {k: v.detach().float().numpy().copy() for k, v in net.state_dict().items()}


def checkpoint_weights(state: dict) -> Weights:
    """The network part of a training checkpoint (as `torch.load` reads it)."""
    return Weights({k: v.float().numpy() for k, v in state["net"].items()}, state["config"], state["episode"])


def _load(net: Plan2PlaceNet, weights: Weights) -> None:
    net.load_state_dict({k: torch.from_numpy(v) for k, v in weights.arrays.items()})


def network_of(weights: Weights) -> Plan2PlaceNet:
    net = Plan2PlaceNet(weights.net)
    _load(net, weights)
    net.use_global = weights.use_global
    return net.eval()


def load_run(path: Path) -> tuple[Plan2PlaceNet, int]:
    """(network, episodes trained) of exported weights (.npz), a checkpoint file or a training folder."""
    if path.suffix == ".npz":
        w = Weights.load(path)
        return network_of(w), w.episode
    state = torch.load(path / "checkpoint.pt" if path.is_dir() else path, weights_only=False)
    return network_of(checkpoint_weights(state)), state["episode"]


def untrained_network(seed: int = 0) -> Plan2PlaceNet:
    """The same network with its initial weights: the baseline that shows what training adds."""
    torch.manual_seed(seed)
    return Plan2PlaceNet(NetConfig()).eval()


def losses(trace: list[dict], aux: bool, imitate: float = 0.0) -> dict[str, torch.Tensor]:
    rewards = [t["reward"] for t in trace]
    returns, g = [], 0.0
    for r in reversed(rewards):
        g = r + GAMMA * g
        returns.append(g)
    ret = torch.tensor(returns[::-1], dtype=torch.float32)
    value = torch.stack([t["value"] for t in trace])
    logp = torch.stack([t["logp"] for t in trace])
    ent = torch.stack([t["entropy"] for t in trace])
    adv = ret - value
    target = torch.tensor([t["r_vlm"] - 1.0 for t in trace], dtype=torch.float32)
    if all("judged" in t for t in trace):  # the greedy-completion teacher's advantages
        policy = -torch.stack([(lp * a).sum() for lp, a in (t["judged"] for t in trace)]).mean()
        if imitate:
            policy = policy - imitate * torch.stack([t["best"] for t in trace]).mean()
    else:
        policy = -(logp * adv.detach()).mean()
    out = {"policy_loss": policy, "value_loss": adv.pow(2).mean(),
           "aux_loss": (value - target).pow(2).mean() if aux else torch.zeros(()), "entropy": ent.mean()}
    out["loss"] = W_POLICY * out["policy_loss"] + W_VALUE * out["value_loss"] + W_AUX * out["aux_loss"] \
        - W_ENTROPY * out["entropy"]
    return out


def start_from(net: Plan2PlaceNet, weights: Path) -> None:
    """Load exported weights (.npz) into a fresh network of the same configuration (fine-tuning); its
    `prior_temp` may differ, for it scales the energy prior of the logits and is not a weight."""
    w = Weights.load(weights)
    if {**w.config["net"], "prior_temp": None} != {**net.cfg.as_dict(), "prior_temp": None}:
        raise ValueError(f"{weights} has the network configuration {w.config['net']}, not this run's "
                         f"{net.cfg.as_dict()}")
    _load(net, w)


def save_checkpoint(path: Path, net, opt, cfg: TrainConfig, episode: int, rng: np.random.Generator) -> None:
    tmp = path.with_suffix(".tmp")
    torch.save({"net": net.state_dict(), "opt": opt.state_dict(), "config": asdict(cfg), "episode": episode,
                "rng": rng.bit_generator.state, "torch_rng": torch.get_rng_state()}, tmp)
    tmp.replace(path)


def training_plans(cfg: TrainConfig) -> Callable[[int], ConstraintPlan]:
    """episode -> its plan: the stored training split in a seeded order, or a freshly planned varied room."""
    if cfg.dataset == VARIED:
        return partial(varied_plan, cfg.seed)
    from models.datasets import load_dataset
    plans = [r.plan for r in load_dataset(cfg.dataset, "train")]
    order = np.random.default_rng(cfg.seed).permutation(len(plans))
    return lambda episode: plans[order[episode % len(plans)]]


def train(cfg: TrainConfig, out_dir: Path, progress: bool = True) -> Path:
    """Train (or resume) in `out_dir`; returns the checkpoint path."""
    out_dir.mkdir(parents=True, exist_ok=True)
    ckpt, log = out_dir / "checkpoint.pt", out_dir / "train.csv"
    torch.manual_seed(cfg.seed)
    torch.set_num_threads(1)
    rng = np.random.default_rng(cfg.seed)
    net = Plan2PlaceNet(NetConfig(**cfg.net))
    opt = torch.optim.Adam(net.parameters(), lr=cfg.lr)
    start = 0
    if ckpt.exists():
        state = torch.load(ckpt, weights_only=False)
        stored = asdict(TrainConfig()) | state["config"]  # options added since the run began take their default
        if stored != asdict(cfg) | {"episodes": stored["episodes"]}:
            raise ValueError(f"{ckpt} was trained with another configuration: {state['config']}")
        net.load_state_dict(state["net"])
        opt.load_state_dict(state["opt"])
        start = state["episode"]
        rng.bit_generator.state = state["rng"]
        torch.set_rng_state(state["torch_rng"])
    elif cfg.init:
        start_from(net, Path(cfg.init))
    (out_dir / "config.json").write_text(json.dumps(asdict(cfg), indent=1))
    plan_of = training_plans(cfg)
    new = not log.exists()
    bar = None
    if progress:
        from tqdm import tqdm
        bar = tqdm(total=cfg.episodes, initial=start, desc="train placement", unit="ep")
    with log.open("a", newline="") as fh:
        writer = csv.DictWriter(fh, LOG_FIELDS)
        if new:
            writer.writeheader()
        batch: list[tuple] = []
        for episode in range(start, cfg.episodes):
            t0 = time.perf_counter()
            plan = plan_of(episode)
            ep, trace = rollout(net, plan, rng, use_global=cfg.use_global, teacher=cfg.teacher, guard=cfg.guard)
            if cfg.repair_reward and trace:
                trace[-1]["reward"] += ep.energy - repaired_energy(ep)
            batch.append((ep, trace, plan, t0))
            if len(batch) == cfg.batch or episode == cfg.episodes - 1:
                parts = [losses(tr, cfg.aux, cfg.imitate) for _, tr, _, _ in batch if tr]
                if parts:
                    loss = torch.stack([p["loss"] for p in parts]).mean()
                    opt.zero_grad()
                    loss.backward()
                    torch.nn.utils.clip_grad_norm_(net.parameters(), 1.0)
                    opt.step()
                for k, (b_ep, tr, b_plan, b_t0) in enumerate(batch):
                    p = parts[min(k, len(parts) - 1)] if parts else {}
                    terms = b_ep.terms
                    writer.writerow({"episode": episode - len(batch) + 1 + k, "plan": b_plan.id,
                                     "objects": len(b_plan.objects), "return": -b_ep.energy,
                                     **{t: round(terms.get(t, 0.0), 5) for t in LOG_FIELDS[4:11]},
                                     **{t: round(float(p[t].detach()), 5) if t in p else "" for t in LOG_FIELDS[11:15]},
                                     "seconds": round(time.perf_counter() - b_t0, 3)})
                fh.flush()
                batch = []
                if (episode + 1) % cfg.checkpoint_every < cfg.batch or episode == cfg.episodes - 1:
                    save_checkpoint(ckpt, net, opt, cfg, episode + 1, rng)
            if bar is not None:
                bar.update(1)
                bar.set_postfix(energy=f"{ep.energy:.2f}")
    if bar is not None:
        bar.close()
    return ckpt


def export_weights(ckpt: Path, out: Path) -> None:
    """The shippable part of a checkpoint: the network's weights (float16) and its configuration, in the
    numpy archive the solver reads without torch (`policy.Weights`)."""
    checkpoint_weights(torch.load(ckpt, weights_only=False)).save(out)


def plot_curves(runs: dict[str, Path], out: Path, window: int = 50) -> Path:
    """Return, energy terms, losses, and E_rel of each run (the paper's figure on the global state)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def smooth(v):
        v = np.asarray(v, float)
        k = max(1, min(window, len(v)))
        return np.convolve(v, np.ones(k) / k, mode="valid")

    data = {name: list(csv.DictReader(p.open())) for name, p in runs.items()}
    panels = [("return", ["return"]), ("energy terms", ["rel", "collision", "oob", "nav", "aff", "missing"]),
              ("losses", ["policy_loss", "value_loss", "aux_loss", "entropy"]), ("E_rel", ["rel"])]
    fig, axes = plt.subplots(1, 4, figsize=(16, 3.5))
    first = next(iter(data))
    for ax, (title, keys) in zip(axes, panels):
        sources = data.items() if title == "E_rel" else [(first, data[first])]
        for name, rows in sources:
            for k in keys:
                vals = [float(r[k]) for r in rows if r.get(k) not in ("", None)]
                if vals:
                    ax.plot(smooth(vals), label=f"{name}" if title == "E_rel" else k)
        ax.set_title(title if title != "E_rel" else "average E_rel (with / without global state)")
        ax.set_xlabel("episode")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=80)
    plt.close(fig)
    return out
