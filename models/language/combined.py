"""The default parser: the rule-based reading and the LoRA language model, each where it is strong.

- The rules run first (well under a millisecond). Hard input they flag (`uncertain`) or cannot read is
  answered by the rules alone: the language model always writes *some* catalogue type, so it must not
  be trusted to invent the objects of an instruction that names none.
- Otherwise the language model's constrained reading decides the task type, the slicing, and which
  named object is the target and which the destination; the rules' choice of target or destination
  replaces the model's only when the model's type is not named in the instruction and the rules' is
  (the model can prefer a frequent training type over a rare one it has seen in no training graph).
- Roles are set by the label rule (key = named by any synonym, inference = required but unnamed, the
  destination is the anchor). When the language model is not available (no adapter, no torch) the
  rules' graph is returned with a message saying so.
"""

from __future__ import annotations

from models.language.base import InstructionError, check_instruction
from models.language.llm.graph_text import LAMPS, GraphFields, graph_of
from models.language.llm.parser import LoraParser, named_types
from models.language.rule_parser import RuleParser
from models.values import TaskGraph
from models.world import normalise_room_type

PARSERS = ("combined", "rules", "lora", "openai")


def rule_fields(graph: TaskGraph) -> GraphFields | None:
    """The four compact fields of a rule-parser graph (None when it has no relations)."""
    if not graph.relations:
        return None
    return GraphFields(graph.task_type, graph.sliced, graph.relations[0][0], graph.relations[-1][2])


class CombinedParser:
    name = "combined"

    def __init__(self, lm: LoraParser | None = None, rules: RuleParser | None = None):
        self.rules = rules or RuleParser()
        self.lm = lm or LoraParser()
        self._lm_error: str | None = None

    def parse(self, instruction: str, room_type: str | None = None) -> TaskGraph:
        text = check_instruction(instruction)
        room = normalise_room_type(room_type) if room_type else None
        try:
            ruled, failure = self.rules.parse(text, room), None
        except InstructionError as e:
            ruled, failure = None, e
        if ruled is not None and ruled.uncertain:
            return ruled
        try:
            decoded = self.lm.read(text, room) if self._lm_error is None else None
        except (FileNotFoundError, ImportError, OSError, RuntimeError) as e:
            self._lm_error, decoded = f"the language model is not available ({e}); rule-based reading", None
        if decoded is None:
            if ruled is None:
                raise failure
            return ruled.model_copy(update={"messages": [*ruled.messages, self._lm_error]})
        return self.merge(text, room, ruled, failure, decoded.fields)

    def merge(self, text: str, room: str | None, ruled: TaskGraph | None, failure: InstructionError | None,
              fields: GraphFields) -> TaskGraph:
        named = named_types(self.rules, text)
        if ruled is None:
            if fields.target not in named:
                raise failure  # the model would be guessing an object the instruction does not name
            graph = self.lm.graph(fields, text, room)
            return graph.model_copy(update={"uncertain": True, "provenance": graph.provenance.model_copy(
                update={"method": self.name}), "messages": [
                f"the rules could not read this instruction ({failure}); the language model's reading is shown"]})
        theirs = rule_fields(ruled)
        if theirs is not None:
            target = fields.target
            if target not in named and theirs.target in named:
                target = theirs.target
            dest = fields.destination
            if fields.destination not in LAMPS and dest not in named and theirs.destination in named \
                    and theirs.destination not in LAMPS and theirs.destination != target:
                dest = theirs.destination
            fields = GraphFields(fields.task_type, fields.sliced, target, dest)
        graph = graph_of(fields, text, room or ruled.room_type, named, self.name)
        if room is None:
            graph = graph.model_copy(update={"room_type": self.rules.infer_room_type([o.type for o in graph.objects])})
        return graph


def make_parser(name: str = "combined", **options):
    """A parser by name: combined (the default), rules, lora, openai (options: base_url, model, api_key)."""
    if name == "rules":
        return RuleParser()
    if name == "lora":
        return LoraParser()
    if name == "combined":
        return CombinedParser()
    if name == "openai":
        from models.language.llm.openai_backend import OpenAIParser
        return OpenAIParser(**options)
    raise ValueError(f"unknown parser {name!r}; expected one of {', '.join(PARSERS)}")
