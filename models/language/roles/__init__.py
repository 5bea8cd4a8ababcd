"""f_theta2: which role (key / anchor / inference) each task object plays, behind one interface.

`RoleClassifier.predict(instruction, types)` -> one role set per type. Two implementations:
`RuleRoles` (lexicon naming + the rule parser's reading of the anchor) and `LearnedRoles` (MiniLM-L6
over "instruction [SEP] object" + a two-layer head, `models/language/roles/model.py`), so callers
can swap them. Both decode with the task-graph structure: every object is key or inference (never
both, never neither) and exactly one object of a graph is the anchor.
"""

from __future__ import annotations

from typing import Protocol

from models.language.alfred import named_types
from models.language.base import InstructionError
from models.world import LAMPS


class RoleClassifier(Protocol):
    name: str

    def predict(self, instruction: str, types: list[str]) -> list[set[str]]: ...


def decode(p_key: list[float], p_anchor: list[float], p_inference: list[float]) -> list[set[str]]:
    """Role sets from per-object probabilities: key or inference by the larger, one anchor (argmax)."""
    out = [{"key"} if k >= i else {"inference"} for k, i in zip(p_key, p_inference, strict=True)]
    if out:
        out[max(range(len(out)), key=p_anchor.__getitem__)].add("anchor")
    return out


class RuleRoles:
    """The rule baseline: key = named in the text (the label rule itself, `named_types`); the anchor =
    the rule parser's anchor when it is one of the objects, else a lamp, else the last object that is
    not the fridge or microwave."""

    name = "rules"

    def __init__(self):
        from models.language.rule_parser import RuleParser
        self.parser = RuleParser.shared()

    def predict(self, instruction: str, types: list[str]) -> list[set[str]]:
        named = named_types(instruction)
        try:
            anchor = self.parser.parse(instruction).anchor
        except InstructionError:
            anchor = None
        pick = [t for t in types if anchor is not None and t == anchor.type] or [t for t in types if t in LAMPS] \
            or [t for t in types if t not in ("Fridge", "Microwave", "Knife")][-1:] or types[-1:]
        key = [1.0 if t in named or (t == "Knife" and "ButterKnife" in named) else 0.0 for t in types]
        return decode(key, [1.0 if t == pick[0] else 0.0 for t in types], [1.0 - k for k in key])
