"""decision.md's fit and gate 1: the shipped network's trunk and critic fine-tuned to the look-ahead's value of
after-states (gen.py's data), then the held-out per-step regret of picking by r + V(after) against greedy's and the
shipped policy's picks. Seeded; writes fit.log's lines to stdout and the fitted weights to OUT-e<epoch>.pt.

    PYTHONPATH=. python app/bench/results/plan2place/afterstate-critic/fit.py [rank] OUT.pt DATA.pkl ...

`rank` (variant B): a loss that ranks each step's judged candidates instead of the MSE on their values.
"""

from __future__ import annotations

import pickle
import sys
from pathlib import Path

import numpy as np
import torch

from models.placement.plan2place.agent import start_from
from models.placement.plan2place.network import Plan2PlaceNet
from models.placement.plan2place.policy import SHIPPED, shipped_weights

EPOCHS, LR, BATCH, SEED = 4, 3e-4, 32, 0
TEMPERATURE = 0.01  # variant B: the softmax of -(final - best) / TEMPERATURE over a step's judged candidates


def value(net: Plan2PlaceNet, obs) -> torch.Tensor:
    f = net.state(obs, fast=True)
    s = torch.zeros(net.cfg.semantic_dim)
    fs = net.compress(net.norm(torch.sigmoid(net.gate(s)) * net.proj(s)))
    return net.critic(torch.cat([f, fs])).squeeze()


def predicted_finals(net: Plan2PlaceNet, step: dict) -> np.ndarray:
    """Each judged candidate's final energy as the critic sees it: its energy after the step minus V(after)."""
    with torch.no_grad():
        v = [0.0 if o is None else float(value(net, o)) for o in step["after"]]
    return step["energy_after"] - np.array(v)


def regrets(net: Plan2PlaceNet, steps: list[dict]) -> dict[str, float]:
    """Mean per-step regret (the pick's final above the best judged) on the steps whose judged finals differ."""
    out = {"greedy": [], "policy": [], "critic": []}
    for st in steps:
        finals, judged = st["finals"], list(st["judged"])
        if np.ptp(finals) < 1e-9:
            continue
        best = finals.min()
        out["greedy"].append(finals[judged.index(0)] - best)
        out["policy"].append(finals[judged.index(st["policy"])] - best)
        out["critic"].append(finals[int(np.argmin(predicted_finals(net, st)))] - best)
    return {k: float(np.mean(v)) for k, v in out.items()} | {"steps": len(out["greedy"])}


def step_loss(net: Plan2PlaceNet, step: dict) -> torch.Tensor:
    """Variant B: cross-entropy between the critic's and the look-ahead's softmax over the step's judged candidates
    that have an after-state."""
    keep = [k for k, o in enumerate(step["after"]) if o is not None]
    pred = torch.tensor(step["energy_after"][keep], dtype=torch.float32) - torch.stack(
        [value(net, step["after"][k]) for k in keep])
    finals = torch.tensor(step["finals"][keep], dtype=torch.float32)
    target = torch.softmax(-(finals - finals.min()) / TEMPERATURE, 0)
    return -(target * torch.log_softmax(-pred / TEMPERATURE, 0)).sum()


def main(out: Path, data: list[Path], rank: bool = False) -> int:
    torch.manual_seed(SEED)
    torch.set_num_threads(1)
    steps = [s for d in data for s in pickle.loads(d.read_bytes())]
    plans = sorted({s["plan"] for s in steps})
    held = set(np.random.default_rng(SEED).permutation(plans)[: len(plans) // 5])
    train = [s for s in steps if s["plan"] not in held]
    test = [s for s in steps if s["plan"] in held]
    samples = [(o, -(f - e)) for s in train for o, f, e in zip(s["after"], s["finals"], s["energy_after"])
               if o is not None]
    if rank:  # one example per step with at least two after-states whose finals differ
        samples = [s for s in train if sum(o is not None for o in s["after"]) > 1 and np.ptp(s["finals"]) > 1e-9]
    net = Plan2PlaceNet(shipped_weights().net)
    start_from(net, Path("models") / SHIPPED)
    print(f"{len(steps)} steps, {len(train)} train / {len(test)} held-out; {len(samples)} "
          f"{'steps' if rank else 'after-states'} to fit")
    print("epoch 0 (shipped critic):", regrets(net, test), flush=True)
    params = [*net.glob.parameters(), *net.sage1.parameters(), *net.sage2.parameters(), *net.attn.parameters(),
              *net.ffn.parameters(), *net.critic.parameters()]
    opt = torch.optim.Adam(params, lr=LR)
    rng = np.random.default_rng(SEED)
    for epoch in range(1, EPOCHS + 1):
        order, total = rng.permutation(len(samples)), 0.0
        for i in range(0, len(order), BATCH):
            batch = [samples[j] for j in order[i:i + BATCH]]
            loss = torch.stack([step_loss(net, b) if rank else (value(net, b[0]) - b[1]) ** 2 for b in batch]).mean()
            opt.zero_grad()
            loss.backward()
            opt.step()
            total += float(loss.detach()) * len(batch)
        torch.save(net.state_dict(), out.with_name(f"{out.stem}-e{epoch}.pt"))
        print(f"epoch {epoch}: train {'CE' if rank else 'MSE'} {total / len(samples):.4f};", regrets(net, test), flush=True)
    return 0


if __name__ == "__main__":
    rank = sys.argv[1] == "rank"
    args = sys.argv[2:] if rank else sys.argv[1:]
    sys.exit(main(Path(args[0]), [Path(p) for p in args[1:]], rank))
