"""f_theta1: the compact graph form, constrained decoding, seeded resumable LoRA training, the parser.

Everything runs on a tiny 2-layer model built from a config; nothing is downloaded (HF_HUB_OFFLINE)."""

from __future__ import annotations

import csv
import os

import pytest

from models.language.alfred import load_annotations
from models.language.llm.graph_text import (GraphTextError, destination_types, fields_of, parse_fields,
                                            target_types)
from models.world import catalogue

pytest.importorskip("peft")


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    from llm_tiny import build_tiny_lm
    return build_tiny_lm(tmp_path_factory.mktemp("tiny-lm"))


def test_compact_form_round_trips_every_alfred_label():
    for row in load_annotations("valid_unseen"):
        fields = fields_of(row)
        assert parse_fields(fields.text()) == fields
        assert set(fields.triplets()) == row.label_triplets()


@pytest.mark.parametrize("text, problem", [
    ("cool | whole | Bread", "expected 4 fields"),
    ("chill | whole | Bread | CounterTop", "unknown task word"),
    ("cool | halved | Bread | CounterTop", "'whole' or 'sliced'"),
    ("cool | whole | Baguette | CounterTop", "not a pickupable"),
    ("look | whole | Book | CounterTop", "not allowed for a look task"),
    ("place | whole | Fridge | CounterTop", "not a pickupable"),
    ("place | whole | Apple | Floor", "not allowed for a place task"),  # the room's structure: nothing to place
])
def test_invalid_model_output_is_refused_with_the_reason(text, problem):
    with pytest.raises(GraphTextError, match=problem):
        parse_fields(text)


def test_untrained_model_still_writes_only_catalogue_types(tiny):
    from models.language.llm.base_model import load_base
    from models.language.llm.decoding import Grammar, constrained_decode, prompt_text
    model, tok = load_base(str(tiny))
    grammar = Grammar(tok)
    cat = catalogue()
    for row in load_annotations("valid_seen")[:5]:
        decoded = constrained_decode(model, grammar, tok(prompt_text(row.instruction, None)).input_ids)
        f = decoded.fields
        assert f.target in target_types() and cat[f.target].pickupable
        assert f.destination in destination_types(f.task_type) and f.destination in cat
        assert decoded.forward_passes <= 4 + 8  # forced tokens cost no extra pass
        # what the model was trained to write for these fields decodes back to them
        assert parse_fields(tok.decode(grammar.target_ids(f), skip_special_tokens=True)) == f


def test_decoding_passes_the_cache_under_the_name_this_transformers_uses(tiny):
    """transformers 5.x renamed the forward's `past_key_values` to `cache` (the old name goes in 5.40): the
    decoding uses whichever the model's forward takes, and reuses it (a few passes, no deprecation warning)."""
    import warnings

    from models.language.adapters import quiet_peft
    from models.language.llm.base_model import load_base
    from models.language.llm.decoding import Grammar, cache_keyword, constrained_decode, prompt_text
    model, tok = load_base(str(tiny))

    class Old:
        def forward(self, input_ids=None, past_key_values=None, use_cache=None): ...

    assert cache_keyword(Old) == "past_key_values"
    from peft import LoraConfig, get_peft_model
    prompt = tok(prompt_text("Put a mug on the table", None)).input_ids
    with warnings.catch_warnings():
        warnings.simplefilter("error", FutureWarning)
        decoded = constrained_decode(model, Grammar(tok), prompt)
    assert decoded.forward_passes <= 12
    # with a LoRA adapter (the shipped parser's case) the name is the base model's, which peft passes on
    with quiet_peft():
        lora = get_peft_model(model, LoraConfig(r=2, lora_alpha=4, target_modules=["q_proj", "v_proj"]))
    with warnings.catch_warnings():
        warnings.simplefilter("error", FutureWarning)
        assert constrained_decode(lora, Grammar(tok), prompt).forward_passes <= 12


def _train(tiny, out, steps, seed=0):
    from models.language.llm.data import training_examples
    from models.language.llm.train import TrainConfig, train
    cfg = TrainConfig(out=str(out), base=str(tiny), seed=seed, max_steps=steps, batch_size=4, save_every=2,
                      val_size=4, limit=60, lr=5e-3, lora_r=4, lora_alpha=8, lora_layers=1)
    return train(cfg, training_examples(), progress=False)


def _losses(out):
    with open(out / "loss.csv") as f:
        return [(r["step"], r["train_loss"]) for r in csv.DictReader(f)]


def test_training_is_seeded_logged_and_resumable(tiny, tmp_path):
    adapter = _train(tiny, tmp_path / "a", 4)
    assert (adapter / "adapter_model.safetensors").exists() and (adapter / "h3ds_meta.json").exists()
    assert (tmp_path / "a" / "loss.png").stat().st_size > 1000
    first = _losses(tmp_path / "a")
    assert [s for s, _ in first] == ["1", "2", "3", "4"]
    assert len({loss for _, loss in first}) > 1  # the loss moves

    # the same seed from scratch gives the same curve; stopping at 2 and resuming to 4 gives it too
    _train(tiny, tmp_path / "b", 4)
    assert _losses(tmp_path / "b") == first
    _train(tiny, tmp_path / "c", 2)
    _train(tiny, tmp_path / "c", 4)
    assert _losses(tmp_path / "c") == first
    # another seed, another curve
    _train(tiny, tmp_path / "d", 4, seed=1)
    assert _losses(tmp_path / "d") != first


def test_lora_parser_loads_an_adapter_offline_and_returns_a_valid_graph(tiny, tmp_path):
    from models.language.llm.parser import LoraParser
    assert os.environ.get("HF_HUB_OFFLINE") == "1"
    adapter = _train(tiny, tmp_path / "run", 2)
    parser = LoraParser(adapter=adapter, base=str(tiny))
    assert not parser.loaded  # lazy: nothing loaded until the first instruction
    graph = parser.parse("Put a chilled bread on the counter", "kitchen")
    assert parser.loaded and graph.provenance.method == "lora"
    assert {o.type for o in graph.objects} <= set(catalogue().types)
    assert graph.anchor is not None and graph.room_type == "kitchen"
    assert graph.target in target_types()


def test_missing_adapter_is_a_clear_error(tmp_path, tiny):
    from models.language.llm.parser import LoraParser
    with pytest.raises(FileNotFoundError, match="no LoRA adapter"):
        LoraParser(adapter=tmp_path, base=str(tiny)).parse("Put the apple in the sink")


def test_train_language_command_writes_curves_and_adapter(tiny, tmp_path, capsys):
    from app.cli import main
    out = tmp_path / "run"
    assert main(["train", "language", "--base", str(tiny), "--out", str(out), "--max-steps", "2", "--batch-size", "2",
                 "--limit", "30", "--lora-r", "2", "--lora-alpha", "4", "--lora-layers", "1", "--save-every", "1"]) == 0
    assert "adapter:" in capsys.readouterr().out
    assert (out / "adapter" / "adapter_config.json").exists() and (out / "loss.png").exists()


def test_training_continues_from_an_adapter_with_its_settings_and_metadata(tiny, tmp_path):
    import json

    from safetensors.torch import load_file

    from models.language.llm.data import training_examples
    from models.language.llm.train import TrainConfig, train
    first = _train(tiny, tmp_path / "a", 2)

    def cont(out, steps, lr):
        cfg = TrainConfig(out=str(out), base=str(tiny), max_steps=steps, batch_size=4, save_every=1, val_size=4,
                          limit=60, lr=lr, init_adapter=str(first))
        return train(cfg, training_examples(), progress=False)
    still = cont(tmp_path / "b", 1, 0.0)  # learning rate 0: the adapter comes back as it was loaded
    before, after = load_file(first / "adapter_model.safetensors"), load_file(still / "adapter_model.safetensors")
    assert before.keys() == after.keys() and all((before[k] == after[k]).all() for k in before)
    assert json.loads((still / "adapter_config.json").read_text())["r"] == 4  # the init adapter's r, not 16
    assert json.loads((still / "h3ds_meta.json").read_text())["init"] == json.loads((first / "h3ds_meta.json").read_text())
    # resumable as a run from scratch: 1 step then on to 3 gives the curve of 3 steps at once
    cont(tmp_path / "c", 3, 5e-3)
    cont(tmp_path / "d", 1, 5e-3)
    cont(tmp_path / "d", 3, 5e-3)
    assert _losses(tmp_path / "d") == _losses(tmp_path / "c") and len({x for _, x in _losses(tmp_path / "c")}) > 1


def test_train_language_command_continues_an_adapter_on_augmented_rows(tiny, tmp_path, monkeypatch, capsys):
    import json

    import app.bench.language as bench
    from app.cli import main
    from models.datasets.language_sets import load_language_set
    first = _train(tiny, tmp_path / "a", 2)
    monkeypatch.setattr(bench, "trained_rows", lambda: list(load_language_set("id_train")[:24]))
    monkeypatch.setattr(bench, "kept_apart_texts", lambda: set())
    out = tmp_path / "run"
    assert main(["train", "language", "--base", str(tiny), "--out", str(out), "--max-steps", "2", "--batch-size", "2",
                 "--init-adapter", str(first), "--augment", "--save-every", "1", "--warmup", "1"]) == 0
    assert "adapter:" in capsys.readouterr().out
    assert (out / "adapter" / "adapter_config.json").exists() and (out / "loss.png").exists()
    assert json.loads((out / "adapter" / "h3ds_meta.json").read_text())["config"]["init_adapter"] == str(first)
