"""`h3ds train roles`: fit the role head on frozen MiniLM features of id_train (seeded, resumable), or with
`lora` the head and LoRA adapters on the encoder together.

Frozen: features are computed once per (instruction, object) pair and cached in chunks under OUT/features/
(an interrupted run resumes from the last chunk). LoRA: each batch goes through the encoder. The state (head,
adapters, optimiser) is checkpointed every epoch (OUT/checkpoint.pt) and a rerun continues from it. Logs
OUT/train.csv (epoch, loss, held-out loss and role accuracies on id_eval) and OUT/curves.png; the final head
goes to OUT/head.pt (LoRA: with the adapter in OUT/, a folder `LearnedRoles` loads).
"""

from __future__ import annotations

import csv
import random
from dataclasses import dataclass
from pathlib import Path

from models.datasets.language_sets import load_language_set
from models.language.roles.model import HEAD, ROLE_COLUMNS, features, lora_encoder, make_head, pooled

CHUNK = 256


@dataclass
class RolesConfig:
    out: str = "runs/roles"
    seed: int = 0
    epochs: int = 40
    lr: float = 1e-3
    batch_size: int = 256
    limit: int | None = 1200  # id_train rows (seeded sample); None = all
    eval_limit: int | None = 250
    lora: bool = False  # train LoRA adapters on the encoder with the head (lr `lora_lr`), batch by batch
    lora_lr: float = 5e-4


def pairs_of(rows) -> tuple[list[tuple[str, str]], list[list[float]]]:
    pairs, targets = [], []
    for r in rows:
        for o in r.label.objects:
            pairs.append((r.instruction, o.type))
            targets.append([float(c in o.roles) for c in ROLE_COLUMNS])
    return pairs, targets


def cached_features(pairs: list[tuple[str, str]], folder: Path, progress: bool = True, compute=features):
    """Features of `pairs` (by `compute`, default the frozen encoder's), computed in chunks of CHUNK and kept in
    `folder` (resumable)."""
    import torch
    from tqdm import tqdm
    folder.mkdir(parents=True, exist_ok=True)
    parts = []
    for i in tqdm(range(0, len(pairs), CHUNK), desc=f"MiniLM features {folder.name}", disable=not progress):
        f = folder / f"{i:07d}.pt"
        if not f.exists():
            torch.save(compute(pairs[i:i + CHUNK]), f)
        parts.append(torch.load(f, weights_only=True))
    return torch.cat(parts) if parts else torch.zeros(0, 768)


def _sample(rows, limit, seed):
    rows = list(rows)
    return rows if limit is None or limit >= len(rows) else random.Random(seed).sample(rows, limit)


def train(cfg: RolesConfig, progress: bool = True) -> Path:
    import torch
    from tqdm import tqdm
    out = Path(cfg.out)
    out.mkdir(parents=True, exist_ok=True)
    torch.manual_seed(cfg.seed)
    tr_pairs, tr_y = pairs_of(_sample(load_language_set("id_train"), cfg.limit, cfg.seed))
    ev_pairs, ev_y = pairs_of(_sample(load_language_set("id_eval"), cfg.eval_limit, cfg.seed))
    y_tr, y_ev = torch.tensor(tr_y), torch.tensor(ev_y)
    head = make_head()
    groups = [{"params": head.parameters(), "lr": cfg.lr}]
    if cfg.lora:
        encoder = lora_encoder()
        groups.append({"params": [p for p in encoder.parameters() if p.requires_grad], "lr": cfg.lora_lr})

        def batch(idx):
            return pooled(encoder, [tr_pairs[i] for i in idx.tolist()])

        def held_out():
            encoder.eval()
            return features(ev_pairs, model=encoder)
    else:
        x_tr = cached_features(tr_pairs, out / "features" / f"train-{cfg.limit}-{cfg.seed}", progress)
        x_ev = cached_features(ev_pairs, out / "features" / f"eval-{cfg.eval_limit}-{cfg.seed}", progress)

        def batch(idx):
            return x_tr[idx]

        def held_out():
            return x_ev
    opt = torch.optim.Adam(groups)
    ckpt, log = out / "checkpoint.pt", out / "train.csv"
    start = 0
    if ckpt.exists():
        state = torch.load(ckpt, weights_only=True)
        head.load_state_dict(state["head"])
        if cfg.lora:
            from peft import set_peft_model_state_dict
            set_peft_model_state_dict(encoder, state["lora"])
        opt.load_state_dict(state["opt"])
        if "rng" in state:  # checkpoints written before it was kept resume without it
            torch.set_rng_state(state["rng"])
        start = state["epoch"]
    if start == 0:
        with log.open("w", newline="") as f:
            csv.writer(f).writerow(["epoch", "loss", "eval_loss", *(f"eval_{c}_accuracy" for c in ROLE_COLUMNS)])
    loss_fn = torch.nn.BCEWithLogitsLoss()
    gen = torch.Generator().manual_seed(cfg.seed)
    for _ in range(start):  # the same shuffles as an uninterrupted run
        torch.randperm(len(tr_pairs), generator=gen)
    for epoch in tqdm(range(start, cfg.epochs), desc="role head epochs", disable=not progress):
        head.train()
        if cfg.lora:
            encoder.train()
        order, total = torch.randperm(len(tr_pairs), generator=gen), 0.0
        for i in range(0, len(order), cfg.batch_size):
            idx = order[i:i + cfg.batch_size]
            loss = loss_fn(head(batch(idx)), y_tr[idx])
            opt.zero_grad()
            loss.backward()
            opt.step()
            total += float(loss.detach()) * len(idx)
        head.eval()
        with torch.no_grad():
            logits = head(held_out())
            acc = ((logits > 0).float() == y_ev).float().mean(0).tolist()
            row = [epoch + 1, total / max(len(tr_pairs), 1), float(loss_fn(logits, y_ev)), *acc]
        with log.open("a", newline="") as f:
            csv.writer(f).writerow([f"{v:.5f}" if isinstance(v, float) else v for v in row])
        state = {"head": head.state_dict(), "opt": opt.state_dict(), "epoch": epoch + 1, "rng": torch.get_rng_state()}
        if cfg.lora:
            from peft import get_peft_model_state_dict
            state["lora"] = get_peft_model_state_dict(encoder)
        torch.save(state, ckpt)
    torch.save(head.state_dict(), out / HEAD)
    if cfg.lora:
        encoder.save_pretrained(out)
    plot(log, out / "curves.png")
    return out if cfg.lora else out / HEAD


def plot(log: Path, png: Path) -> Path:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    with log.open() as f:
        rows = list(csv.DictReader(f))
    ep = [int(r["epoch"]) for r in rows]
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.2))
    a.plot(ep, [float(r["loss"]) for r in rows], label="train BCE")
    a.plot(ep, [float(r["eval_loss"]) for r in rows], label="id_eval BCE")
    a.set_xlabel("epoch"), a.legend()
    for c in ROLE_COLUMNS:
        b.plot(ep, [float(r[f"eval_{c}_accuracy"]) for r in rows], label=c)
    b.set_xlabel("epoch"), b.set_ylabel("id_eval accuracy (threshold 0.5)"), b.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=90)
    plt.close(fig)
    return png
