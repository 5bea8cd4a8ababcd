"""The default parser: rules + the LoRA language model, each where it is strong, rules as the fallback."""

from __future__ import annotations

import pytest

from models.language import InstructionError, RuleParser
from models.language.combined import CombinedParser, make_parser
from models.language.llm.graph_text import GraphFields
from models.language.llm.parser import LoraParser

pytest.importorskip("peft")


@pytest.fixture(scope="module")
def tiny_adapter(tmp_path_factory):
    from llm_tiny import build_tiny_lm

    from models.language.llm.data import training_examples
    from models.language.llm.train import TrainConfig, train
    base = build_tiny_lm(tmp_path_factory.mktemp("tiny-lm"))
    out = tmp_path_factory.mktemp("run")
    adapter = train(TrainConfig(out=str(out), base=str(base), max_steps=2, batch_size=4, val_size=2, limit=20,
                                lora_r=4, lora_alpha=8, lora_layers=1), training_examples(), progress=False)
    return adapter, base


@pytest.fixture(scope="module")
def combined(tiny_adapter):
    adapter, base = tiny_adapter
    return CombinedParser(lm=LoraParser(adapter=adapter, base=str(base)))


def test_model_reading_kept_when_it_names_what_the_instruction_names(combined):
    text = "Put a chilled apple on the table"
    ruled = RuleParser().parse(text, "kitchen")
    fields = GraphFields("pick_cool_then_place_in_recep", False, "Apple", "DiningTable")
    graph = combined.merge(text, "kitchen", ruled, None, fields)
    assert graph.provenance.method == "combined"
    assert set(map(tuple, graph.relations)) == {("Apple", "cooled_in", "Fridge"), ("Apple", "placed_at", "DiningTable")}
    roles = {o.type: o.roles for o in graph.objects}
    assert roles == {"Apple": ["key"], "Fridge": ["inference"], "DiningTable": ["key", "anchor"]}


def test_unnamed_model_types_give_way_to_named_rule_types(combined):
    text = "Put a chilled apple on the counter"
    ruled = RuleParser().parse(text, "kitchen")
    # the model wrote a frequent training target and destination that the instruction does not name
    fields = GraphFields("pick_cool_then_place_in_recep", False, "Tomato", "DiningTable")
    graph = combined.merge(text, "kitchen", ruled, None, fields)
    assert ("Apple", "placed_at", "CounterTop") in graph.relations
    assert "Tomato" not in {o.type for o in graph.objects}
    # its task reading (cool) is kept: the rules only fix the object names
    assert graph.task_type == "pick_cool_then_place_in_recep"


def test_instruction_naming_no_object_is_an_error_not_an_invented_type(combined):
    with pytest.raises(InstructionError, match="no object to pick up"):
        combined.parse("Hello there, how are you today?")


def test_rules_read_misses_are_flagged_uncertain_when_the_model_names_a_named_type(tiny_adapter):
    adapter, base = tiny_adapter  # rules-first (not the default policy): the model answers the rules' refusals
    combined = CombinedParser(lm=LoraParser(adapter=adapter, base=str(base)), policy="rules-first")
    text = "Grab the apple"
    failure = InstructionError("no object to pick up was recognised")
    fields = GraphFields("pick_and_place_simple", False, "Apple", "CounterTop")
    graph = combined.merge(text, None, None, failure, fields)
    assert graph.uncertain and "could not read" in graph.messages[0]
    with pytest.raises(InstructionError):
        combined.merge(text, None, None, failure, GraphFields("pick_and_place_simple", False, "Mug", "CounterTop"))


def test_end_to_end_graph_is_valid_and_fast_to_construct(combined):
    graph = combined.parse("Put a chilled bread on the counter", "kitchen")
    assert graph.provenance.method == "combined" and graph.anchor is not None
    assert {"Bread", "CounterTop"} <= {o.type for o in graph.objects}  # both named: the rules hold them


def test_without_a_language_model_the_rules_answer_and_say_so(tmp_path):
    parser = CombinedParser(lm=LoraParser(adapter=tmp_path))
    graph = parser.parse("Put a chilled bread on the counter", "kitchen")
    assert graph.provenance.method == "rules"
    assert any("language model is not available" in m for m in graph.messages)


def test_parsers_by_name():
    assert make_parser("rules").name == "rules"
    assert make_parser("combined").name == "combined"
    assert make_parser("combined").policy == "rules-first-fieldwise"
    assert make_parser("openai", base_url="http://127.0.0.1:9/v1").name == "openai"
    with pytest.raises(ValueError, match="unknown parser"):
        make_parser("gpt")


def test_policies_differ_where_both_readings_name_a_type(tiny_adapter):
    adapter, base = tiny_adapter
    lm = LoraParser(adapter=adapter, base=str(base))
    text = "Put the mug from the table in the sink"
    ruled = RuleParser().parse(text, "kitchen")
    fields = GraphFields("pick_and_place_simple", False, "Mug", "DiningTable")  # a named but wrong destination
    rules_first = CombinedParser(lm=lm, policy="rules-first").merge(text, "kitchen", ruled, None, fields)
    lm_first = CombinedParser(lm=lm, policy="lm-first").merge(text, "kitchen", ruled, None, fields)
    assert rules_first.relations[-1] == ruled.relations[-1]
    assert lm_first.relations[-1] == ("Mug", "placed_at", "DiningTable")
    # a task type the model is sure of replaces the rules' cue-less default; an unsure one does not
    heat = GraphFields("pick_heat_then_place_in_recep", False, "Mug", "SinkBasin")
    sure = CombinedParser(lm=lm).merge(text, "kitchen", ruled, None, heat, (0.95, 1.0, 1.0, 1.0))
    unsure = CombinedParser(lm=lm).merge(text, "kitchen", ruled, None, heat, (0.5, 1.0, 1.0, 1.0))
    assert ruled.task_type == "pick_and_place_simple"
    assert sure.task_type == "pick_heat_then_place_in_recep" and unsure.task_type == ruled.task_type
    # but never a cue word the rules read ("chilled" -> cool)
    chilled = "Put a chilled mug in the sink"
    ruled = RuleParser().parse(chilled, "kitchen")
    cool = CombinedParser(lm=lm).merge(chilled, "kitchen", ruled, None, heat, (0.99, 1.0, 1.0, 1.0))
    assert cool.task_type == "pick_cool_then_place_in_recep"
    with pytest.raises(ValueError, match="unknown policy"):
        CombinedParser(lm=lm, policy="vote")


def test_strict_policy_keeps_the_rules_refusals_and_lamp_alone_and_never_asks_the_model():
    from models.language.combined import STRICT

    class NoModel(LoraParser):
        def read(self, text, room):
            raise AssertionError("the strict policy must not ask the model here")
    rules_first, strict = CombinedParser(policy="rules-first"), CombinedParser(lm=NoModel(), policy=STRICT)
    refused = "Grab it from the fridge"  # the rules find nothing to pick up
    with pytest.raises(InstructionError) as failure:
        RuleParser().parse(refused, "kitchen")
    fields = GraphFields("pick_and_place_simple", False, "Fridge", "CounterTop")
    assert rules_first.merge(refused, "kitchen", None, failure.value, fields).uncertain  # the model's reading shown
    with pytest.raises(InstructionError, match="no object to pick up"):
        strict.merge(refused, "kitchen", None, failure.value, fields)
    with pytest.raises(InstructionError, match="no object to pick up"):
        strict.parse(refused, "kitchen")
    lamp = "Turn on the lamp"  # the rules read a lamp alone, no relation
    ruled = RuleParser().parse(lamp, "bedroom")
    assert ruled.relations == []
    look = GraphFields("look_at_obj_in_light", False, "Book", "DeskLamp")
    assert rules_first.merge(lamp, "bedroom", ruled, None, look).relations  # rules-first takes the model's reading
    assert strict.merge(lamp, "bedroom", ruled, None, look) == ruled == strict.parse(lamp, "bedroom")
    # elsewhere the strict policy is rules-first
    text = "Put the mug from the table in the sink"
    ruled = RuleParser().parse(text, "kitchen")
    heat = GraphFields("pick_heat_then_place_in_recep", False, "Mug", "SinkBasin")
    sure = (0.95, 1.0, 1.0, 1.0)
    assert strict.merge(text, "kitchen", ruled, None, heat, sure) == rules_first.merge(text, "kitchen", ruled, None,
                                                                                     heat, sure)


def test_default_parser_is_combined_fieldwise_and_loads_nothing_until_the_first_instruction(monkeypatch):
    import os
    import subprocess
    import sys

    from app.pipeline import Pipeline
    from models.language.combined import DEFAULT_PARSER, FIELDWISE
    from models.language.room_type import EmbeddingRoomType
    monkeypatch.delenv("H3DS_PARSER", raising=False)
    parser = Pipeline().parser
    assert DEFAULT_PARSER == "combined" and isinstance(parser, CombinedParser) and parser.policy == FIELDWISE
    assert isinstance(parser.room_types, EmbeddingRoomType) and parser.room_types.memory is None
    assert not parser.lm.loaded
    monkeypatch.setenv("H3DS_PARSER", "rules")
    assert isinstance(Pipeline().parser, RuleParser)
    # start-up stays light: building the default pipeline imports no torch
    code = "import sys; from app.pipeline import Pipeline; Pipeline(); print('torch' in sys.modules)"
    env = {k: v for k, v in os.environ.items() if k != "H3DS_PARSER"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert out.stdout.strip() == "False", out.stderr[-2000:]


def test_room_type_of_an_instruction_given_without_one_comes_from_the_classifier():
    from models.language.combined import STRICT

    class Rooms:
        def __init__(self, error=None):
            self.error, self.asked = error, []

        def predict(self, texts):
            if self.error:
                raise self.error
            self.asked += texts
            return ["bathroom"] * len(texts)

    class NoModel(LoraParser):
        def read(self, text, room):
            raise OSError("no model here")
    rooms = Rooms()
    parser = CombinedParser(lm=NoModel(), policy=STRICT, room_types=rooms)
    text = "Put a chilled bread on the counter"
    assert RuleParser().parse(text).room_type == "kitchen"  # the frequency rule
    assert parser.parse(text).room_type == "bathroom" and rooms.asked == [text]
    assert parser.parse(text, "kitchen").room_type == "kitchen" and rooms.asked == [text]  # given: not asked
    broken = CombinedParser(lm=NoModel(), policy=STRICT, room_types=Rooms(ImportError("no torch")))
    graph = broken.parse(text)
    assert graph.room_type == "kitchen" and any("room-type classifier is not available" in m for m in graph.messages)


def test_fieldwise_policy_takes_each_model_field_it_is_sure_of_or_that_the_text_names():
    from models.language.combined import FIELD_CONFIDENCE, FIELDWISE, STRICT

    class NoModel(LoraParser):
        def read(self, text, room):
            raise AssertionError("merge is given the model's fields; the model must not be asked")
    fieldwise, strict = CombinedParser(lm=NoModel(), policy=FIELDWISE), CombinedParser(lm=NoModel(), policy=STRICT)
    sure, unsure = (0.99,) * 4, (0.5,) * 4
    assert 0.5 < FIELD_CONFIDENCE <= 0.99

    def fields(policy, text, model, confidence):
        ruled = RuleParser().parse(text, "kitchen")
        graph = policy.merge(text, "kitchen", ruled, None, model, confidence)
        return graph.task_type, graph.sliced, graph.relations[0][0], graph.relations[-1][2]
    # both readings name a target: the model's (here it read the object acted on, the rules the tool)
    text = "Use a knife to remove the stem of a cooled tomato."
    model = GraphFields("pick_cool_then_place_in_recep", False, "Tomato", "CounterTop")
    assert fields(fieldwise, text, model, unsure)[2] == "Tomato" and fields(strict, text, model, sure)[2] == "Knife"
    # a model target the text does not name never replaces a named one, however sure (rare objects)
    text = "Put a chilled ladle on the counter"
    model = GraphFields("pick_cool_then_place_in_recep", False, "Spoon", "CounterTop")
    assert fields(fieldwise, text, model, sure)[2] == "Ladle"
    # slicing and a named destination: the model's when it is sure, the rules' when it is not
    text = "Put a knife on a small black table."
    model = GraphFields("pick_and_place_simple", True, "Knife", "SideTable")
    assert fields(fieldwise, text, model, sure)[1:] == (True, "Knife", "SideTable")
    assert fields(fieldwise, text, model, unsure)[1:] == (False, "Knife", "DiningTable")
    assert fields(strict, text, model, sure)[1:] == (False, "Knife", "DiningTable")
    # a task type over the rules' cue-less default at FIELD_CONFIDENCE (below the strict policy's 0.9)
    text = "Put the mug from the table in the sink"
    heat = GraphFields("pick_heat_then_place_in_recep", False, "Mug", "SinkBasin")
    p = (FIELD_CONFIDENCE, 1.0, 1.0, 1.0)
    assert fields(fieldwise, text, heat, p)[0] == heat.task_type
    assert fields(strict, text, heat, p)[0] == "pick_and_place_simple"


def test_fieldwise_policy_answers_a_refusal_only_with_a_named_or_sure_target_and_keeps_a_lamp_alone():
    from models.language.combined import FIELDWISE

    class NoModel(LoraParser):
        def read(self, text, room):
            raise AssertionError("a lamp alone stands: the model must not be asked")
    fieldwise = CombinedParser(lm=NoModel(), policy=FIELDWISE)
    text = "Put a tube on a toilet paper holder."  # the rules find no object to pick up
    with pytest.raises(InstructionError) as failure:
        RuleParser().parse(text, "bathroom")
    tube = GraphFields("pick_and_place_simple", False, "ToiletPaper", "ToiletPaperHanger")
    graph = fieldwise.merge(text, "bathroom", None, failure.value, tube, (1.0, 1.0, 0.95, 1.0))
    assert graph.uncertain and ("ToiletPaper", "placed_at", "ToiletPaperHanger") in graph.relations
    with pytest.raises(InstructionError):  # an unnamed target the model is unsure of: the refusal stands
        fieldwise.merge(text, "bathroom", None, failure.value, tube, (1.0, 1.0, 0.5, 1.0))
    nothing = "Hello there, how are you today?"  # names no type: never an invented reading, however sure
    with pytest.raises(InstructionError):
        fieldwise.merge(nothing, None, None, InstructionError("no object"), tube, (1.0,) * 4)
    lamp = "Turn on the lamp"
    ruled = RuleParser().parse(lamp, "bedroom")
    look = GraphFields("look_at_obj_in_light", False, "Book", "DeskLamp")
    assert fieldwise.merge(lamp, "bedroom", ruled, None, look) == ruled == fieldwise.parse(lamp, "bedroom")
