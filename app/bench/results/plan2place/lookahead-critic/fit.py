"""Fine-tune the shipped actor towards the look-ahead's judgments (gen.py's steps), offline: per step, a
cross-entropy of the actor's distribution over its candidate subset against the judged candidates' target
distribution softmax(-(final - best final) / TAU). The plans are split (a fifth held out, by plan id) and the
held-out steps' regret is reported: the final energy of the pick (among the judged) above the best judged one,
for greedy's pick (lowest immediate energy), the shipped policy's and the fine-tuned one's, after each epoch.

    PYTHONPATH=. python app/bench/results/plan2place/lookahead-critic/fit.py STEPS.pkl OUT.npz [EPOCHS] [LR]
"""

from __future__ import annotations

import pickle
import sys
import zlib
from pathlib import Path

import numpy as np
import torch

from models.placement.plan2place.agent import arrays_of, network_of
from models.placement.plan2place.features import Observation
from models.placement.plan2place.policy import Weights, shipped_weights

TAU = 0.01
BATCH = 32
SEED = 0


def held_out(plan_id: str) -> bool:
    return zlib.crc32(plan_id.encode()) % 5 == 0


def obs_of(s: dict) -> Observation:
    return Observation(s["glob"], s["nodes"], s["edges"], s["cands"], np.arange(len(s["cands"])))


def regret(steps: list[dict], pick) -> tuple[float, float]:
    """(mean regret, share of steps at a best judged candidate) of `pick(step) -> position in judged`."""
    r = np.array([s["finals"][pick(s)] - s["finals"].min() for s in steps])
    return float(r.mean()), float((r <= 1e-9).mean())


def main(src: Path, out: Path, epochs: int = 4, lr: float = 3e-4) -> int:
    steps = [s for s in pickle.loads(src.read_bytes())["steps"] if len(s["judged"]) > 1]
    fit, test = [s for s in steps if not held_out(s["plan"])], [s for s in steps if held_out(s["plan"])]
    informative = [s for s in test if np.ptp(s["finals"]) > 1e-9]
    print(f"{len(fit)} fitting steps, {len(test)} held-out ({len(informative)} where the judged finals differ)")
    torch.manual_seed(SEED)
    rng = np.random.default_rng(SEED)
    net = network_of(shipped_weights()).train()
    opt = torch.optim.Adam(net.parameters(), lr=lr)

    def net_pick(s: dict) -> int:
        with torch.no_grad():
            logits = net._logits(net.state(obs_of(s), fast=True), obs_of(s)).numpy()
        return int(np.argmax(logits[s["judged"]]))

    def report(label: str) -> None:
        greedy = regret(informative, lambda s: 0)
        policy = regret(informative, lambda s: int(np.flatnonzero(s["judged"] == s["policy"])[0]))
        print(f"{label}: held-out regret / share at best: greedy {greedy[0]:.4f} / {greedy[1]:.3f}, shipped "
              f"{policy[0]:.4f} / {policy[1]:.3f}, fine-tuned {' / '.join(f'{v:.4f}' for v in regret(informative, net_pick))}",
              flush=True)

    report("before")
    for epoch in range(epochs):
        order = rng.permutation(len(fit))
        total = 0.0
        for b in range(0, len(order), BATCH):
            loss = torch.zeros(())
            for i in order[b:b + BATCH]:
                s = fit[i]
                obs = obs_of(s)
                logp = torch.log_softmax(net._logits(net.state(obs, fast=True), obs), 0)[torch.from_numpy(s["judged"])]
                target = torch.softmax(torch.from_numpy(-(s["finals"] - s["finals"].min()) / TAU).float(), 0)
                loss = loss - (target * logp).sum()
            loss = loss / len(order[b:b + BATCH])
            opt.zero_grad()
            loss.backward()
            opt.step()
            total += float(loss.detach()) * len(order[b:b + BATCH])
        report(f"epoch {epoch + 1} (loss {total / len(fit):.4f})")
        w = shipped_weights()
        Weights(arrays_of(net), w.config, w.episode).save(out.with_name(f"{out.stem}-e{epoch + 1}.npz"))
    return 0


if __name__ == "__main__":
    a = sys.argv[1:]
    sys.exit(main(Path(a[0]), Path(a[1]), *(int(a[2]),) if len(a) > 2 else (), *(float(a[3]),) if len(a) > 3 else ()))
