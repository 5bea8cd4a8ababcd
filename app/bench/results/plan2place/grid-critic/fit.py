"""decision.md's fit and gate 1: a small convolutional critic of after-state rasters (gen.py's data), fitted with
the centred MSE and with the rank loss; the loss and epoch of lowest validation regret are chosen, then the held-out
per-step regret is set against greedy's and the shipped policy's picks. Seeded; prints fit.log's lines and writes
each epoch's weights to OUT-<loss>-e<epoch>.pt.

    PYTHONPATH=. python app/bench/results/plan2place/grid-critic/fit.py OUT.pt DATA.pkl ...
"""

from __future__ import annotations

import pickle
import sys
from pathlib import Path

import numpy as np
import torch
from torch import nn

sys.path.insert(0, str(Path(__file__).parent))
from floor import JUDGED, LAYERS, NUMBERS, SIDE  # noqa: E402

EPOCHS, LR, BATCH, SEED = 20, 1e-3, 64, 0
TEMPERATURE = 0.01  # the rank loss: softmax of -(final - best) / TEMPERATURE over a step's candidates
WIDTH = JUDGED + 1  # candidates per step at most: the lowest-energy ones and the policy's pick


class GridCritic(nn.Module):
    """Rasters (B, LAYERS, SIDE, SIDE) and numbers (B, NUMBERS) -> the predicted final energy minus the energy after
    the step."""

    def __init__(self, channels: int = LAYERS, numbers: int = NUMBERS):
        super().__init__()
        self.conv = nn.Sequential(
            nn.Conv2d(channels, 16, 3, padding=1), nn.ReLU(), nn.MaxPool2d(2),
            nn.Conv2d(16, 32, 3, padding=1), nn.ReLU(), nn.MaxPool2d(2),
            nn.Conv2d(32, 32, 3, padding=1), nn.ReLU())
        self.head = nn.Sequential(nn.Linear(64 + numbers, 64), nn.ReLU(), nn.Linear(64, 1))

    def forward(self, rasters: torch.Tensor, numbers: torch.Tensor) -> torch.Tensor:
        h = self.conv(rasters)
        pooled = torch.cat([h.mean((2, 3)), h.amax((2, 3))], 1)
        return self.head(torch.cat([pooled, numbers], 1)).squeeze(1)


def tensors(steps: list[dict]) -> dict[str, torch.Tensor]:
    """The steps padded to WIDTH candidates: rasters, numbers, finals, energies after, mask, greedy and policy index."""
    s = len(steps)
    r = np.zeros((s, WIDTH, LAYERS, SIDE, SIDE), np.uint8)
    n = np.zeros((s, WIDTH, NUMBERS), np.float32)
    f, e, m = np.zeros((s, WIDTH)), np.zeros((s, WIDTH)), np.zeros((s, WIDTH), bool)
    pol = np.zeros(s, np.int64)
    for i, st in enumerate(steps):
        k = len(st["judged"])
        r[i, :k], n[i, :k], f[i, :k], e[i, :k], m[i, :k] = st["rasters"], st["numbers"], st["finals"], \
            st["energy_after"], True
        pol[i] = list(st["judged"]).index(st["policy"])
    return {"r": torch.tensor(r), "n": torch.tensor(n), "f": torch.tensor(f, dtype=torch.float32),
            "e": torch.tensor(e, dtype=torch.float32), "m": torch.tensor(m), "policy": torch.tensor(pol)}


def predicted(net: GridCritic, t: dict, idx: torch.Tensor) -> torch.Tensor:
    """(b, WIDTH) predicted finals of steps `idx` (+inf where padded)."""
    r = t["r"][idx].float().div(255).flatten(0, 1)
    n = t["n"][idx].flatten(0, 1)
    out = net(r, n).view(len(idx), WIDTH) + t["e"][idx]
    return out.masked_fill(~t["m"][idx], float("inf"))


def loss_of(kind: str, pred: torch.Tensor, t: dict, idx: torch.Tensor) -> torch.Tensor:
    m, f = t["m"][idx], t["f"][idx]
    if kind == "mse":  # centred on each step's mean
        k = m.sum(1, keepdim=True)
        p = torch.where(m, pred, 0.0)
        pc = p - p.sum(1, keepdim=True) / k
        fc = f - torch.where(m, f, 0.0).sum(1, keepdim=True) / k
        return (torch.where(m, pc - fc, 0.0) ** 2).sum() / m.sum()
    best = torch.where(m, f, float("inf")).min(1, keepdim=True).values
    target = torch.softmax(torch.where(m, -(f - best) / TEMPERATURE, float("-inf")), 1)
    logp = torch.log_softmax(-pred / TEMPERATURE, 1)
    return -(target * torch.where(m, logp, 0.0)).sum(1).mean()


def regrets(net: GridCritic | None, t: dict, idx: torch.Tensor) -> dict[str, float]:
    """Mean per-step regret (the pick's final above the best judged) over the steps whose judged finals differ."""
    f = torch.where(t["m"][idx], t["f"][idx], float("inf"))
    best = f.min(1).values
    spread = torch.where(t["m"][idx], t["f"][idx], float("-inf")).max(1).values - best
    keep = spread > 1e-9
    out = {"greedy": (f[:, 0] - best)[keep].mean().item(),
           "policy": (f.gather(1, t["policy"][idx][:, None])[:, 0] - best)[keep].mean().item()}
    if net is not None:
        with torch.no_grad():
            pick = torch.cat([predicted(net, t, idx[i:i + 256]).argmin(1) for i in range(0, len(idx), 256)])
        out["critic"] = (f.gather(1, pick[:, None])[:, 0] - best)[keep].mean().item()
    return out | {"steps": int(keep.sum())}


def split(steps: list[dict]) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    """Step indices of the train / validation / held-out plans (70 / 10 / 20 %)."""
    plans = sorted({s["plan"] for s in steps})
    order = np.random.default_rng(SEED).permutation(len(plans))
    part = {plans[j]: 0 if r < 0.7 * len(plans) else 1 if r < 0.8 * len(plans) else 2 for r, j in enumerate(order)}
    which = np.array([part[s["plan"]] for s in steps])
    return tuple(torch.tensor(np.flatnonzero(which == k)) for k in range(3))


def fit(kind: str, t: dict, train: torch.Tensor, val: torch.Tensor, out: Path) -> list[tuple[int, float]]:
    torch.manual_seed(SEED)
    net = GridCritic()
    opt = torch.optim.Adam(net.parameters(), lr=LR)
    rng = np.random.default_rng(SEED)
    scores = []
    for epoch in range(1, EPOCHS + 1):
        order, total = train[rng.permutation(len(train))], 0.0
        for i in range(0, len(order), BATCH):
            idx = order[i:i + BATCH]
            loss = loss_of(kind, predicted(net, t, idx), t, idx)
            opt.zero_grad()
            loss.backward()
            opt.step()
            total += float(loss.detach()) * len(idx)
        torch.save(net.state_dict(), out.with_name(f"{out.stem}-{kind}-e{epoch}.pt"))
        r = regrets(net, t, val)
        scores.append((epoch, r["critic"]))
        print(f"{kind} epoch {epoch}: train loss {total / len(train):.4f}; validation {r}", flush=True)
    return scores


def main(out: Path, data: list[Path]) -> int:
    torch.set_num_threads(2)
    steps = [s for d in data for s in pickle.loads(d.read_bytes())]
    t = tensors(steps)
    train, val, held = split(steps)
    print(f"{len(steps)} steps: {len(train)} train / {len(val)} validation / {len(held)} held-out")
    print("validation, no critic:", regrets(None, t, val))
    print("held-out, no critic:", regrets(None, t, held), flush=True)
    best = min(((v, kind, e) for kind in ("mse", "rank") for e, v in fit(kind, t, train, val, out)))
    _, kind, epoch = best
    net = GridCritic()
    net.load_state_dict(torch.load(out.with_name(f"{out.stem}-{kind}-e{epoch}.pt")))
    r = regrets(net, t, held)
    print(f"chosen on validation: {kind} epoch {epoch}; held-out {r}")
    print("gate 1:", "passes" if r["critic"] < min(r["greedy"], r["policy"]) else "fails")
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), [Path(p) for p in sys.argv[2:]]))
