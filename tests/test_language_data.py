"""ALFRED label derivation (interfaces.md roles) and the language sets of issue 10."""

import random

import pytest

from models.datasets import language_sets as ls
from models.language.alfred import Annotation, load_annotations, named_types


def _row(text, task="pick_cool_then_place_in_recep", target="Bread", parent="CounterTop", toggle="",
         sliced=False, plan="FloorPlan3"):
    return Annotation("train", task, text, target, parent, toggle, sliced, plan)


def _roles(graph):
    return {o.type: o.roles for o in graph.objects}


def test_roles_follow_naming():
    chilled = _roles(_row("Put a chilled bread on the counter").label_graph())
    assert chilled == {"Bread": ["key"], "CounterTop": ["key", "anchor"], "Fridge": ["inference"]}
    named = _roles(_row("Put bread in the fridge, then on the counter").label_graph())
    assert named["Fridge"] == ["key"]
    unnamed_place = _roles(_row("Chill the bread and put it away").label_graph())
    assert unnamed_place["CounterTop"] == ["anchor", "inference"]


def test_lamp_and_knife_roles():
    look = _row("Look at the watch under the lamp", task="look_at_obj_in_light", target="Watch", parent="",
                toggle="DeskLamp", plan="FloorPlan301").label_graph()
    assert _roles(look) == {"Watch": ["key"], "DeskLamp": ["key", "anchor"]}
    dark = _row("Examine the watch", task="look_at_obj_in_light", target="Watch", parent="", toggle="FloorLamp",
                plan="FloorPlan201").label_graph()
    assert _roles(dark)["FloorLamp"] == ["anchor", "inference"]
    sliced = _row("Put a slice of apple cut with a butter knife on the table", task="pick_and_place_simple",
                  target="Apple", parent="DiningTable", sliced=True).label_graph()
    assert _roles(sliced)["Knife"] == ["key"] and ("Apple", "sliced_with", "Knife") in sliced.relations


def test_misspellings_name_objects_but_common_words_do_not():
    assert "Fridge" in named_types("Put the cold apple in the refrigerater")
    assert "Plate" not in named_types("Place the apple on the counter")
    assert "RemoteControl" not in named_types("Remove the apple from the counter")


def test_every_alfred_row_gets_a_valid_graph_whose_roles_match_naming():
    rows = load_annotations("valid_seen")
    for a in rows:
        g = a.label_graph()
        named = named_types(a.instruction)
        assert {o.type for o in g.objects} == a.label_objects()
        assert len(g.with_role("anchor")) == 1
        for o in g.objects:
            assert ("key" in o.roles) != ("inference" in o.roles)
            if o.type != "Knife":
                assert ("key" in o.roles) == (o.type in named)


def test_splits_never_share_a_sentence():
    train = {ls.text_key(r.instruction) for r in ls.load_language_set("id_train")}
    for name in ("id_eval", "valid_unseen", "ts", "os"):
        rows = ls.load_language_set(name)
        assert rows and not train & {ls.text_key(r.instruction) for r in rows}, name
    alfred_train = {ls.text_key(a.instruction) for a in load_annotations("train")}
    dedup = ls.load_language_set("valid_unseen_dedup")
    assert len(dedup) < len(ls.load_language_set("valid_unseen"))
    assert not alfred_train & {ls.text_key(r.instruction) for r in dedup}


def test_stored_eval_sets_are_what_the_code_builds():
    id_eval = ls._alfred("valid_seen")
    assert [ls._encode(r) for r in id_eval] == [ls._encode(r) for r in ls.load_language_set("id_eval")]
    assert [ls._encode(r) for r in ls.text_shift(id_eval)] == [ls._encode(r) for r in ls.load_language_set("ts")]
    assert [ls._encode(r) for r in ls.object_shift(id_eval)] == [ls._encode(r) for r in ls.load_language_set("os")]


def test_text_shift_changes_words_and_keeps_the_label():
    by_source = {r.source: r for r in ls.load_language_set("id_eval")}
    ts = ls.load_language_set("ts")
    assert len(ts) >= 0.9 * len(by_source)
    for r in ts:
        original = by_source[r.source]
        assert ls.text_key(r.instruction) != ls.text_key(original.instruction)
        assert ls._same_label(r.label, original.label)


def test_object_shift_uses_rare_sensible_targets():
    rare = ls.rare_targets()
    by_source = {r.source: r for r in ls.load_language_set("id_eval")}
    rows = ls.load_language_set("os")
    assert len(rows) >= 150
    for r in rows:
        assert r.label.target in rare and r.label.target != by_source[r.source].label.target
        assert r.label.target in named_types(r.instruction)
        assert {t for t in r.label_objects()} - {r.label.target} == \
            by_source[r.source].label_objects() - {by_source[r.source].label.target}


def test_rephrase_is_seeded():
    text = "Put a chilled apple on the counter."
    assert ls.rephrase(text, random.Random(1)) == ls.rephrase(text, random.Random(1))


def test_unknown_set_is_a_clear_error():
    with pytest.raises(KeyError, match="known: id_train"):
        ls.load_language_set("nope")


def test_label_review_reads_every_evaluation_row_once_or_twice():
    verdicts = ls.review_verdicts()
    keys = {ls.review_key(n, r) for n in ls.REVIEWED_SETS for r in ls.load_language_set(n)}
    assert set(verdicts) == keys
    assert {len(v) for v in verdicts.values()} == {1, 2}
    assert sum(len(v) == 2 for v in verdicts.values()) == 48 + 36  # 6 rows of each batch read again: 8 + 6 batches
    assert all(set(v) <= set(ls.REVIEW_VERDICTS) for v in verdicts.values())
    assert 0 < sum(v != ("ok",) for v in verdicts.values()) < len(verdicts) / 2


def test_label_review_names_an_unknown_verdict():
    good = '{"source": "valid_seen:1", "verdict": "ok", "note": "", "reader": 0}\n'
    assert ls.parse_review(good + good.replace('"reader": 0', '"reader": 1')) == {"valid_seen:1": ("ok", "ok")}
    with pytest.raises(ValueError, match="'maybe' for valid_seen:2"):
        ls.parse_review(good + '{"source": "valid_seen:2", "verdict": "maybe", "note": "", "reader": 0}\n')


def test_label_agrees_needs_every_reader_s_ok():
    rows = {r.source: r for r in ls.load_language_set("id_eval")}
    assert not ls.label_agrees("id_eval", rows["valid_seen:467"])  # "a heated cup", labelled Mug: S
    assert ls.label_agrees("id_eval", rows["valid_seen:110"])  # "the spray bottle in the garbage bin"
    assert ls.label_agrees("id_eval_dedup", rows["valid_seen:110"])
    assert set(ls.review_verdicts()["valid_seen:295"]) == {"ok", "S"}  # read twice, the readers disagreed
    assert not ls.label_agrees("id_eval", rows["valid_seen:295"])
    with pytest.raises(KeyError, match="did not read 'id_train'"):
        ls.label_agrees("id_train", rows["valid_seen:110"])
