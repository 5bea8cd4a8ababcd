"""LoRA fine-tuning of a causal LM to write compact task graphs (`h3ds train language`).

Any Hugging Face causal LM folder works as the base (`--base /path/to/falcon-7b` on a GPU machine);
the default is the bundled SmolLM2-135M-Instruct. Seeded (data order, room-type dropout, LoRA init),
resumable (the last checkpoint holds adapter, optimiser, scheduler and RNG states), logged to
`loss.csv` and `loss.png` in the output folder. The loss is on the answer tokens only. With
`init_adapter` the run continues training a trained adapter (its LoRA settings, not the config's), and
the adapters it writes keep that adapter's metadata under "init" (which rows it had trained on).
"""

from __future__ import annotations

import csv
import json
import math
import random
import time
from dataclasses import asdict, dataclass
from pathlib import Path

from models.language.adapters import quiet_peft
from models.language.llm.base_model import SMOLLM2, load_base
from models.language.llm.graph_text import GraphFields

META_FILE = "h3ds_meta.json"
INIT_META = "init_meta.json"  # in a run folder: the metadata of the adapter the run started from


@dataclass
class TrainConfig:
    out: str
    base: str = SMOLLM2
    seed: int = 0
    epochs: float = 1.0
    max_steps: int | None = None
    batch_size: int = 16
    lr: float = 1e-3
    warmup: int = 20
    # the paper's LoRA: r 32, alpha 43, dropout 0.05 (here r 16 and alpha scaled to keep alpha / r; see README)
    lora_r: int = 16
    lora_alpha: float = 21.5
    lora_dropout: float = 0.05
    lora_layers: int | None = 15  # LoRA on the top N transformer blocks (None: all)
    room_dropout: float = 0.3  # share of examples shown "Room: unknown"
    save_every: int = 50
    val_size: int = 48
    limit: int | None = None  # use only the first N training examples (tests)
    threads: int | None = None
    init_adapter: str | None = None  # continue training this adapter folder (LoRA settings taken from it)


@dataclass(frozen=True)
class Example:
    instruction: str
    room_type: str | None
    fields: GraphFields


def _encode(grammar, ex: Example) -> tuple[list[int], list[int]]:
    from models.language.llm.decoding import prompt_text
    prompt = grammar.tok(prompt_text(ex.instruction, ex.room_type)).input_ids
    answer = grammar.target_ids(ex.fields)
    return prompt + answer, [-100] * len(prompt) + answer


def _batch(grammar, examples: list[Example]):
    import torch
    pairs = [_encode(grammar, e) for e in examples]
    width = max(len(i) for i, _ in pairs)
    pad = grammar.tok.pad_token_id if grammar.tok.pad_token_id is not None else grammar.eos
    ids = torch.full((len(pairs), width), pad)
    labels = torch.full((len(pairs), width), -100)
    mask = torch.zeros((len(pairs), width), dtype=torch.long)
    for k, (i, lab) in enumerate(pairs):
        ids[k, :len(i)] = torch.tensor(i)
        labels[k, :len(i)] = torch.tensor(lab)
        mask[k, :len(i)] = 1
    return ids, labels, mask


def linear_names(model) -> list[str]:
    """Every linear projection inside the transformer blocks (q/k/v/o and the MLP for Llama-style models,
    query_key_value / dense / dense_h_to_4h / dense_4h_to_h for Falcon), by its attribute name."""
    import torch
    out_layer = model.get_output_embeddings()
    return sorted({name.rsplit(".", 1)[-1] for name, m in model.named_modules()
                   if isinstance(m, torch.nn.Linear) and m is not out_layer})


def lora_model(model, cfg: TrainConfig):
    from peft import LoraConfig, get_peft_model
    n_layers = getattr(model.config, "num_hidden_layers", None)
    layers = None
    if cfg.lora_layers and n_layers and cfg.lora_layers < n_layers:
        layers = list(range(n_layers - cfg.lora_layers, n_layers))
    config = LoraConfig(r=cfg.lora_r, lora_alpha=cfg.lora_alpha, lora_dropout=cfg.lora_dropout,
                        target_modules=linear_names(model), layers_to_transform=layers, task_type="CAUSAL_LM")
    with quiet_peft():
        return get_peft_model(model, config)


def from_adapter(model, adapter: str):
    """The base with a trained adapter, trainable, its LoRA weights in float32 (shipped adapters are
    float16)."""
    from peft import PeftModel
    with quiet_peft():
        model = PeftModel.from_pretrained(model, adapter, is_trainable=True)
    for p in model.parameters():
        if p.requires_grad:
            p.data = p.data.float()
    return model


def _init_meta(run: Path) -> dict:
    """{"init": metadata of the adapter the run started from}, or {} for a run from scratch."""
    path = Path(run) / INIT_META
    return {"init": json.loads(path.read_text())} if path.exists() else {}


def _plot(rows: list[dict], path: Path) -> None:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(7, 4))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    ax.plot([r["step"] for r in rows], [r["train_loss"] for r in rows], label="train loss (answer tokens)", lw=0.8)
    val = [r for r in rows if r.get("val_loss") not in (None, "")]
    if val:
        ax.plot([r["step"] for r in val], [float(r["val_loss"]) for r in val], "o-", label="held-out loss")
        ax2 = ax.twinx()
        ax2.plot([r["step"] for r in val], [float(r["val_exact"]) for r in val], "s--", color="green",
                 label="held-out exact graph")
        ax2.set_ylim(0, 1)
        ax2.set_ylabel("exact-match share")
        ax2.legend(loc="center right")
    ax.set_yscale("log")
    ax.set_xlabel("step")
    ax.set_ylabel("cross-entropy")
    ax.legend(loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def _evaluate(model, grammar, examples: list[Example]) -> tuple[float, float]:
    """Held-out answer loss and share of exactly right graphs under constrained decoding."""
    import torch

    from models.language.llm.decoding import constrained_decode, prompt_text
    model.eval()
    with torch.inference_mode():
        losses = []
        for k in range(0, len(examples), 16):
            ids, labels, mask = _batch(grammar, examples[k:k + 16])
            losses.append(float(model(input_ids=ids, attention_mask=mask, labels=labels).loss))
        exact = sum(constrained_decode(model, grammar, grammar.tok(prompt_text(e.instruction, e.room_type)).input_ids)
                    .fields == e.fields for e in examples)
    model.train()
    return sum(losses) / len(losses), exact / len(examples)


def save_adapter(model, folder: Path, cfg: TrainConfig, extra: dict) -> None:
    """The adapter in float16 (half the bytes; it is cast back to the model's dtype on loading)."""
    import torch
    from safetensors.torch import load_file, save_file
    model.save_pretrained(folder)
    weights = folder / "adapter_model.safetensors"
    save_file({k: v.to(torch.float16) for k, v in load_file(weights).items()}, weights)
    (folder / META_FILE).write_text(json.dumps({"config": asdict(cfg), **extra}, indent=2) + "\n")


def export_checkpoint(run: Path, dest: Path) -> Path:
    """The run's last checkpoint as a shippable adapter in `dest` (float16, with the run's config and
    last held-out figures): to ship a model while its training goes on."""
    import shutil

    import torch
    from safetensors.torch import load_file, save_file
    ckpt = Path(run) / "checkpoint-last"
    state = torch.load(ckpt / "state.pt", weights_only=False)
    dest.mkdir(parents=True, exist_ok=True)
    shutil.copy(ckpt / "adapter_config.json", dest / "adapter_config.json")
    save_file({k: v.to(torch.float16) for k, v in load_file(ckpt / "adapter_model.safetensors").items()},
              dest / "adapter_model.safetensors")
    last = next((r for r in reversed(state["log"]) if r["val_loss"] != ""), {})
    config = json.loads((Path(run) / "config.json").read_text()) if (Path(run) / "config.json").exists() else {}
    (dest / META_FILE).write_text(json.dumps({"config": config, "steps": state["step"],
                                              "held_out_loss": last.get("val_loss"),
                                              "held_out_exact": last.get("val_exact"),
                                              "seconds": state["log"][-1]["seconds"], **_init_meta(run)},
                                             indent=2) + "\n")
    return dest


def train(cfg: TrainConfig, train_rows: list[Example], progress: bool = True) -> Path:
    """Fine-tune; returns the folder of the final adapter (`OUT/adapter`)."""
    import numpy as np
    import torch
    from tqdm import tqdm

    from models.language.llm.decoding import Grammar

    out = Path(cfg.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "config.json").write_text(json.dumps(asdict(cfg), indent=2) + "\n")
    if cfg.threads:
        torch.set_num_threads(cfg.threads)
    random.seed(cfg.seed)
    np.random.seed(cfg.seed)
    torch.manual_seed(cfg.seed)

    rows = list(train_rows)[:cfg.limit] if cfg.limit else list(train_rows)
    order_rng = random.Random(cfg.seed)
    order_rng.shuffle(rows)
    n_val = min(cfg.val_size, len(rows) // 5)  # a tiny run keeps most of its examples for training
    val, rows = rows[:n_val], rows[n_val:]
    room_rng = random.Random(cfg.seed + 1)
    rows = [Example(r.instruction, None if room_rng.random() < cfg.room_dropout else r.room_type, r.fields)
            for r in rows]

    model, tok = load_base(cfg.base)
    model.config.use_cache = False
    if cfg.init_adapter:
        init_meta = Path(cfg.init_adapter) / META_FILE
        if init_meta.exists():
            (out / INIT_META).write_text(init_meta.read_text())
        model = from_adapter(model, cfg.init_adapter)
    else:
        model = lora_model(model, cfg)
    grammar = Grammar(tok)
    steps_per_epoch = math.ceil(len(rows) / cfg.batch_size)
    if not rows or not val:
        raise ValueError(f"too few training examples ({len(rows) + len(val)}) to hold some out")
    total = cfg.max_steps or max(1, int(cfg.epochs * steps_per_epoch))
    params = [p for p in model.parameters() if p.requires_grad]
    opt = torch.optim.AdamW(params, lr=cfg.lr, weight_decay=0.0)

    def lr_at(step: int) -> float:
        if step < cfg.warmup:
            return (step + 1) / cfg.warmup
        return 0.1 + 0.9 * 0.5 * (1 + math.cos(math.pi * (step - cfg.warmup) / max(1, total - cfg.warmup)))
    sched = torch.optim.lr_scheduler.LambdaLR(opt, lr_at)

    ckpt, log_rows, step = out / "checkpoint-last", [], 0
    if (ckpt / "state.pt").exists():
        from peft import set_peft_model_state_dict
        from safetensors.torch import load_file
        set_peft_model_state_dict(model, load_file(ckpt / "adapter_model.safetensors"))
        state = torch.load(ckpt / "state.pt", weights_only=False)
        opt.load_state_dict(state["optimizer"])
        sched.load_state_dict(state["scheduler"])
        torch.set_rng_state(state["torch_rng"])
        step, log_rows = state["step"], state["log"]
        print(f"resumed from {ckpt} at step {step} of {total}", flush=True)

    def checkpoint() -> None:
        tmp = out / "checkpoint-tmp"
        model.save_pretrained(tmp)
        torch.save({"optimizer": opt.state_dict(), "scheduler": sched.state_dict(), "step": step,
                    "torch_rng": torch.get_rng_state(), "log": log_rows}, tmp / "state.pt")
        if ckpt.exists():
            import shutil
            shutil.rmtree(ckpt)
        tmp.rename(ckpt)
        with open(out / "loss.csv", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=["step", "epoch", "train_loss", "lr", "seconds", "val_loss", "val_exact"])
            w.writeheader()
            w.writerows(log_rows)
        _plot(log_rows, out / "loss.png")

    model.train()
    started = time.perf_counter() - (log_rows[-1]["seconds"] if log_rows else 0.0)
    bar = tqdm(total=total, initial=step, disable=not progress, desc="train language", unit="step")
    while step < total:
        epoch, k = divmod(step, steps_per_epoch)
        perm = list(range(len(rows)))
        random.Random(cfg.seed * 1000 + epoch).shuffle(perm)
        batch = [rows[i] for i in perm[k * cfg.batch_size:(k + 1) * cfg.batch_size]]
        ids, labels, mask = _batch(grammar, batch)
        loss = model(input_ids=ids, attention_mask=mask, labels=labels).loss
        loss.backward()
        torch.nn.utils.clip_grad_norm_(params, 1.0)
        opt.step()
        sched.step()
        opt.zero_grad(set_to_none=True)
        step += 1
        row = {"step": step, "epoch": round(step / steps_per_epoch, 4), "train_loss": round(loss.item(), 5),
               "lr": sched.get_last_lr()[0], "seconds": round(time.perf_counter() - started, 1),
               "val_loss": "", "val_exact": ""}
        log_rows.append(row)
        bar.update(1)
        bar.set_postfix(loss=f"{row['train_loss']:.4f}")
        if step % cfg.save_every == 0 or step == total:
            vl, ve = _evaluate(model, grammar, val)
            row.update(val_loss=round(vl, 5), val_exact=round(ve, 4))
            bar.write(f"step {step}: held-out loss {vl:.4f}, exact graphs {ve:.3f}")
            checkpoint()
    bar.close()
    final = out / "adapter"
    last = next((r for r in reversed(log_rows) if r["val_loss"] != ""), {})
    save_adapter(model, final, cfg, {"steps": step, "train_examples": len(rows), "held_out": len(val),
                                     "held_out_loss": last.get("val_loss"), "held_out_exact": last.get("val_exact"),
                                     "seconds": log_rows[-1]["seconds"] if log_rows else 0, **_init_meta(out)})
    return final
