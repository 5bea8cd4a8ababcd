"""`h3ds bench language` scores from cached model readings, without loading the model."""

import json

from app.bench.language import lora_readings, read_all, reviewed_rows, score_parsers, unseen_train_rows
from models.datasets.language_sets import load_language_set
from models.language import RuleParser
from models.language.combined import CombinedParser, rule_fields


def test_cached_readings_are_scored_without_the_model(tmp_path):
    rows = load_language_set("id_eval")[:20]
    cache = tmp_path / "readings.jsonl"
    with open(cache, "w") as f:  # a model that writes the label: lora scores 100 %
        for r in rows:
            fields = rule_fields(r.label)
            f.write(json.dumps({"text": " ".join(r.instruction.split()), "room": r.room_type, "seconds": 0.5,
                                "fields": [fields.task_type, fields.sliced, fields.target, fields.destination],
                                "logprob": [0.0, 0.0, 0.0, 0.0]}) + "\n")

    class NoModel:
        def load(self):
            raise AssertionError("every reading is cached; the model must not load")

    readings = lora_readings(rows, NoModel(), cache, progress=False)
    rules = RuleParser()
    graphs, seconds = read_all(rows, readings, rules, {"combined": CombinedParser(rules=rules)})
    scored = score_parsers(rows, graphs, seconds)
    assert scored["lora"]["object_f1"] == scored["lora"]["irecall"] == 1.0 and scored["lora"]["ged"] == 0
    assert scored["lora"]["key_accuracy"] == scored["lora"]["anchor_accuracy"] == 1.0
    assert scored["rules"]["object_f1"] < 1.0 and 500 <= scored["lora"]["p50_ms"] < 501
    assert set(scored) == {"rules", "lora", "combined"}


def test_policy_rows_are_unseen_by_the_adapter_and_the_review_has_100_rows():
    rows = unseen_train_rows(50)
    assert len(rows) == 50 and len({r.source for r in rows}) == 50
    assert len(unseen_train_rows()) > 5000  # 0.45 epoch of 10,738 rows trained; the rest never seen
    review = reviewed_rows()
    assert len(review) == 100 and sum(ok for _, ok in review) == 80


def test_room_type_by_embedding_similarity(monkeypatch):
    from types import SimpleNamespace

    import models.language.room_type as room_type
    monkeypatch.setattr(room_type, "K", 1)
    memory = [SimpleNamespace(instruction=t, room_type=room) for room, texts in {
        "kitchen": ["Put the chilled apple on the counter", "Heat a mug in the microwave", "Slice the bread"],
        "bathroom": ["Put the soap bar in the bathtub", "Hang the towel by the sink", "Put toilet paper on the toilet"],
    }.items() for t in texts]
    knn = room_type.EmbeddingRoomType(memory)
    assert knn.predict(["Put a chilled apple on the countertop", "Put the bar of soap in the bathtub"]) == \
        ["kitchen", "bathroom"]


def test_confirmation_sets_are_apart_from_training_the_policy_rows_the_review_and_the_room_memory():
    from app.bench.language import (CONFIRM_SEED, CONFIRMATION, POLICY_ROWS, _adapter_split, confirmation_rows,
                                    confirmation_sets)
    from models.datasets.language_sets import SEED, text_key
    from models.language.room_type import memory_rows
    rows = confirmation_rows(40)
    assert len(rows) == 40 and rows == confirmation_rows(40)  # deterministic
    train, seen, _ = _adapter_split()
    texts = {text_key(r.instruction) for r in rows}
    assert len(texts) == 40
    assert not texts & {text_key(train[i].instruction) for i in seen}
    assert not texts & {text_key(r.instruction) for r in unseen_train_rows(POLICY_ROWS)}
    assert not texts & {text_key(r.instruction) for r in memory_rows()}
    assert not texts & {text_key(r.instruction) for r, _ in reviewed_rows()}
    sets = confirmation_sets(40)
    assert list(sets) == list(CONFIRMATION) and list(sets[CONFIRMATION[0]]) == rows and CONFIRM_SEED != SEED
    sources = {r.source for r in rows}
    for shifted in (sets[CONFIRMATION[1]], sets[CONFIRMATION[2]]):
        assert shifted and {r.source for r in shifted} <= sources
        assert not {text_key(r.instruction) for r in shifted} & texts  # every row rewritten


def test_decision_rules_need_every_confirmation_set():
    from app.bench.language import CONFIRMATION, decisions
    even = {"object_f1": 0.9, "irecall": 0.8}
    scored = {k: {"rules": even, "strict": dict(even)} for k in CONFIRMATION}
    rooms = {k: {"rules": 0.8, "minilm": 0.9} for k in CONFIRMATION}
    assert decisions(scored, rooms, "strict") == {"strict_default": True, "minilm_room_type": True}
    scored[CONFIRMATION[2]]["strict"]["irecall"] = 0.79
    rooms[CONFIRMATION[1]]["minilm"] = 0.8  # equal is not above
    assert decisions(scored, rooms, "strict") == {"strict_default": False, "minilm_room_type": False}


def test_shipped_room_type_memory_is_the_seeded_rows_embedded():
    import numpy as np

    from models.language.room_type import EmbeddingRoomType, embed, memory_rows, shipped_memory
    rows = memory_rows()
    with np.load(shipped_memory()) as saved:
        assert list(saved["sources"]) == [r.source for r in rows]
        assert list(saved["rooms"]) == [r.room_type for r in rows]
        stored = saved["embeddings"][:3].astype(np.float32)
    assert np.abs(stored - embed([r.instruction for r in rows[:3]])).max() < 2e-3  # float16
    knn = EmbeddingRoomType()
    assert knn.memory is None and knn.predict(["Put a chilled apple on the counter"]) == ["kitchen"]
    assert knn.memory.shape == (len(rows), 384)


def test_latency_counts_the_model_only_where_it_is_asked():
    from types import SimpleNamespace

    from models.language.combined import FIELDWISE, STRICT
    rows = [SimpleNamespace(instruction=t, room_type="bedroom") for t in ("Turn on the lamp", "Put the book on the bed")]
    readings = {(r.instruction, r.room_type): {"fields": ["look_at_obj_in_light", False, "Book", "DeskLamp"],
                                              "logprob": [0.0] * 4, "seconds": 0.5} for r in rows}
    rules = RuleParser()
    parsers = {"strict": CombinedParser(rules=rules, policy=STRICT), "first": CombinedParser(rules=rules, policy="rules-first"),
               "fieldwise": CombinedParser(rules=rules, policy=FIELDWISE)}
    _, seconds = read_all(rows, readings, rules, parsers)
    lamp, book = [(r.instruction, r.room_type) for r in rows]
    assert seconds["strict"][lamp] < 0.1 and seconds["first"][lamp] >= 0.5  # a lamp alone: the rules stand
    assert seconds["fieldwise"][lamp] < 0.1 and seconds["fieldwise"][book] >= 0.5
    assert seconds["strict"][book] >= 0.5


def test_augmented_rows_keep_the_policy_and_confirmation_rows_unseen_and_use_only_the_training_pool():
    from app.bench.language import POLICY_ROWS, confirmation_rows, kept_apart_texts, trained_rows
    from models.datasets.language_sets import object_shift, rare_target_pools, text_key
    from models.language.llm.data import AUGMENT_SEED, augmented_examples
    trained, kept_apart = trained_rows(), kept_apart_texts()
    policy, confirm = unseen_train_rows(POLICY_ROWS), confirmation_rows()
    assert {text_key(r.instruction) for r in [*policy, *confirm]} <= kept_apart
    assert not {r.source for r in trained} & {r.source for r in [*policy, *confirm]}
    rows = trained[:150] + policy[:5] + confirm[:5]  # rows that must stay unseen are dropped, rewrites too
    examples = augmented_examples(rows, kept_apart)
    assert not {text_key(e.instruction) for e in examples} & kept_apart
    pool, held_out = rare_target_pools()
    assert len(pool) == len(held_out) and not set(pool) & set(held_out) and rare_target_pools() == (pool, held_out)
    kept = [r for r in rows if text_key(r.instruction) not in kept_apart]
    assert len(kept) <= 150 and examples[:len(kept)] and {e.instruction for e in examples[:len(kept)]} == \
        {r.instruction for r in kept}
    shifted = object_shift(kept, AUGMENT_SEED, pool)  # the object-shift part of the examples
    assert shifted and {r.label.target for r in shifted} <= set(pool)
    assert {e.instruction for e in examples} >= {r.instruction for r in shifted if text_key(r.instruction) not in kept_apart}
    as_is = {e.fields.target for e in examples[:len(kept)]}
    assert {e.fields.target for e in examples} - as_is <= set(pool)  # a held-out type only where ALFRED named it


def test_each_adapter_has_its_own_readings_cache(tmp_path):
    from app.bench.language import readings_cache
    for name, data in (("a", b"1"), ("b", b"2"), ("c", b"1")):
        (tmp_path / name).mkdir()
        (tmp_path / name / "adapter_model.safetensors").write_bytes(data)
    assert readings_cache(tmp_path / "a") != readings_cache(tmp_path / "b")
    assert readings_cache(tmp_path / "a") == readings_cache(tmp_path / "c")


def test_fresh_confirmation_sets_are_apart_from_every_row_read_before():
    from app.bench.language import (CONFIRM_SEED, FRESH, FRESH_SEED, POLICY_ROWS, _adapter_split, _development_texts,
                                    confirmation_sets, fresh_confirmation_rows, fresh_confirmation_sets,
                                    kept_apart_texts, read_before_texts)
    from models.datasets.language_sets import SEED, text_key
    from models.language.room_type import memory_rows
    rows = fresh_confirmation_rows(60)
    assert len(rows) == 60 and rows == fresh_confirmation_rows(60)  # deterministic
    texts = {text_key(r.instruction) for r in rows}
    assert len(texts) == 60
    train, seen, _ = _adapter_split()
    assert not texts & {text_key(train[i].instruction) for i in seen}
    # policy rows (and the dev rows among them), the confirmation sets, every evaluation set
    assert not texts & kept_apart_texts()
    assert not texts & {text_key(r.instruction) for s in confirmation_sets().values() for r in s}
    assert not texts & {text_key(r.instruction) for r in unseen_train_rows(POLICY_ROWS)}
    assert not texts & {text_key(r.instruction) for r in memory_rows()}
    assert not texts & {text_key(r.instruction) for r, _ in reviewed_rows()}
    assert not texts & _development_texts()  # dev ts / os, read row by row while designing the policy
    assert FRESH_SEED not in (SEED, CONFIRM_SEED, 13, 21)  # evaluation, confirmation, development, augmentation
    sets = fresh_confirmation_sets(60)
    assert list(sets) == list(FRESH) and list(sets[FRESH[0]]) == rows
    sources = {r.source for r in rows}
    for shifted in (sets[FRESH[1]], sets[FRESH[2]]):
        assert shifted and {r.source for r in shifted} <= sources
        assert not {text_key(r.instruction) for r in shifted} & (texts | read_before_texts())


def test_fieldwise_decision_needs_every_fresh_set_and_the_strict_policy_s_ged():
    from app.bench.language import FRESH, fieldwise_decision
    scored = {k: {"rules": {"object_f1": 0.9, "irecall": 0.8, "ged": 1.1},
                  "strict": {"object_f1": 0.91, "irecall": 0.8, "ged": 1.0},
                  "fieldwise": {"object_f1": 0.9, "irecall": 0.81, "ged": 1.0}} for k in FRESH}
    assert fieldwise_decision(scored, "fieldwise", "strict")  # equal is enough
    scored[FRESH[2]]["fieldwise"]["ged"] = 1.01
    assert not fieldwise_decision(scored, "fieldwise", "strict")
    scored[FRESH[2]]["fieldwise"]["ged"] = 0.9
    scored[FRESH[1]]["fieldwise"]["object_f1"] = 0.89
    assert not fieldwise_decision(scored, "fieldwise", "strict")
