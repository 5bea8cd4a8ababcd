import pytest

from app.bench.parser import score
from models.language import InstructionError, RuleParser
from models.language.alfred import load_annotations


@pytest.fixture(scope="module")
def parser():
    return RuleParser()


def test_the_interfaces_example(parser):
    g = parser.parse("Put a chilled bread on the counter", "kitchen")
    assert g.task_type == "pick_cool_then_place_in_recep"
    assert {o.type: o.roles for o in g.objects} == {"Bread": ["key"], "CounterTop": ["key", "anchor"],
                                                    "Fridge": ["inference"]}
    assert set(g.relations) == {("Bread", "cooled_in", "Fridge"), ("Bread", "placed_at", "CounterTop")}


@pytest.mark.parametrize("text,task,objects", [
    ("Put the heated tomato in the fridge", "pick_heat_then_place_in_recep", {"Tomato", "Microwave", "Fridge"}),
    ("Examine a remote control under the floor lamp", "look_at_obj_in_light", {"RemoteControl", "FloorLamp"}),
    ("Place a slice of apple on the table", "pick_and_place_simple", {"Apple", "Knife", "DiningTable"}),
    ("Move the salt shaker from the shelf into the cabinet", "pick_and_place_simple", {"SaltShaker", "Cabinet"}),
    ("Warm up a mug and put it in the coffee maker", "pick_heat_then_place_in_recep",
     {"Mug", "Microwave", "CoffeeMachine"}),
])
def test_alfred_task_semantics(parser, text, task, objects):
    g = parser.parse(text, "kitchen")
    assert g.task_type == task and {o.type for o in g.objects} == objects


def test_unnamed_required_objects_are_inferred_and_the_anchor_is_the_destination(parser):
    g = parser.parse("Put a cold apple in the sink", "kitchen")
    roles = {o.type: o.roles for o in g.objects}
    assert roles["Fridge"] == ["inference"] and "anchor" in roles["SinkBasin"]


def test_room_type_is_inferred_when_not_given(parser):
    assert parser.parse("Put a chilled bread on the counter").room_type == "kitchen"
    assert parser.parse("Put the toilet paper on the toilet").room_type == "bathroom"


@pytest.mark.parametrize("bad,message", [
    ("", "empty"), ("   ", "empty"), ("x" * 10_000, "10000 characters"), ("put \x00\x01 it", "binary"),
    ("!!! ???", "no words"), ("Sing a song", "no object"),
])
def test_bad_instructions_name_the_problem(parser, bad, message):
    with pytest.raises(InstructionError, match=message):
        parser.parse(bad)


def test_rule_parser_quality_on_alfred_valid_unseen(parser):
    """The baseline's measured figures (the benchmark prints them); a regression fails here."""
    result = score(parser, load_annotations("valid_unseen"))
    assert result["n"] == 518
    assert result["object_f1"] > 0.88 and result["triplet_recall"] > 0.8 and result["task_type_accuracy"] > 0.9
