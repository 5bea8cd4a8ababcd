"""ALFRED annotations (bundled) and the task-graph labels interfaces.md derives from their pddl params."""

from __future__ import annotations

import gzip
import json
from dataclasses import dataclass
from functools import cache
from importlib import resources

from models.values import Provenance, TaskGraph, TaskObject

# ALFRED's pddl names that the AI2-THOR catalogue spells differently.
ALFRED_TYPE_NAMES = {"Glassbottle": "Bottle"}
SCENE_ROOMS = ((1, 30, "kitchen"), (201, 230, "living room"), (301, 330, "bedroom"), (401, 430, "bathroom"))


@dataclass(frozen=True)
class Annotation:
    split: str
    task_type: str
    instruction: str
    object_target: str
    parent_target: str
    toggle_target: str
    sliced: bool
    floor_plan: str

    @property
    def room_type(self) -> str:
        n = int(self.floor_plan.removeprefix("FloorPlan"))
        return next(room for lo, hi, room in SCENE_ROOMS if lo <= n <= hi)

    def label_objects(self) -> set[str]:
        """The task's object types: target, receptacle, fridge / microwave, lamp, knife."""
        return {t for t, _, o in self.label_triplets() for t in (t, o)} or {self.target}

    @property
    def target(self) -> str:
        return ALFRED_TYPE_NAMES.get(self.object_target, self.object_target)

    def label_triplets(self) -> set[tuple[str, str, str]]:
        t = self.target
        out = set()
        if self.sliced:
            out.add((t, "sliced_with", "Knife"))
        if self.task_type == "pick_cool_then_place_in_recep":
            out.add((t, "cooled_in", "Fridge"))
        if self.task_type == "pick_heat_then_place_in_recep":
            out.add((t, "heated_in", "Microwave"))
        if self.task_type == "look_at_obj_in_light":
            out.add((t, "examined_under", self.toggle_target))
        else:
            out.add((t, "placed_at", ALFRED_TYPE_NAMES.get(self.parent_target, self.parent_target)))
        return out


    def task_graph(self, named: frozenset[str] | None = None) -> TaskGraph:
        """The task graph of interfaces.md for this annotation.

        With `named` (the types the instruction names, see `named_types`) the roles follow the label
        rules exactly: key = named, inference = required but not named, anchor = the final receptacle or
        the lamp. Without it (the planners' datasets) the target and the receptacle or lamp count as
        named and the fridge, microwave and knife as inferred, which is what annotators usually write.
        """
        roles: dict[str, list[str]] = {}
        for obj, rel, other in sorted(self.label_triplets(), key=lambda t: RELATION_ORDER.index(t[1])):
            anchor = rel in ("placed_at", "examined_under")
            if named is None:
                roles.setdefault(obj, ["key"])
                roles.setdefault(other, ["key", "anchor"] if anchor else ["inference"])
                continue
            for t, is_anchor in ((obj, False), (other, anchor)):
                found = roles.setdefault(t, [])
                said = "key" if _is_named(t, named) else "inference"
                found.extend(r for r in (said, "anchor" if is_anchor else None) if r and r not in found)
        if named is not None:
            roles = {t: sorted(r, key=ROLE_ORDER.index) for t, r in roles.items()}
        return TaskGraph(instruction=self.instruction, room_type=self.room_type, task_type=self.task_type,
                         objects=[TaskObject(type=t, roles=r) for t, r in roles.items()],
                         relations=sorted(self.label_triplets(), key=lambda t: RELATION_ORDER.index(t[1])),
                         sliced=self.sliced, provenance=Provenance(stage="task_graph", method="alfred-labels"))


    def label_graph(self) -> TaskGraph:
        """The labelled task graph: roles by what this instruction actually names."""
        return self.task_graph(named_types(self.instruction))


RELATION_ORDER = ("sliced_with", "cooled_in", "heated_in", "placed_at", "examined_under")
ROLE_ORDER = ("key", "anchor", "inference")
# A butter knife named for "sliced with Knife" still names the knife the task needs.
NAMED_ALIASES = {"Knife": ("Knife", "ButterKnife")}
# Common words one letter away from an object name ("place" / "plate"); never read as misspellings.
NOT_MISSPELLINGS = frozenset({"place", "placed", "places", "plates", "table", "tables", "class", "glass",
                              "apply", "bread", "break", "cable", "pants", "paint", "stand", "stove", "store",
                              "shelf", "shell", "spoon", "sponge", "watch", "match", "water", "later", "cards",
                              "lamps", "large", "light", "right", "night", "sight", "tight", "eight", "front",
                              "remove", "removed", "bowls"})
MIN_FUZZY_CHARS = 5


def _is_named(type_name: str, named: frozenset[str]) -> bool:
    return any(t in named for t in NAMED_ALIASES.get(type_name, (type_name,)))


def _deletes(word: str) -> set[str]:
    return {word} | {word[:i] + word[i + 1:] for i in range(len(word))}


@cache
def _fuzzy_index() -> dict[str, frozenset[str]]:
    """one-deletion variant of every one-word object name of >= 5 letters -> the types it names."""
    from models.world import catalogue
    index: dict[str, set[str]] = {}
    for phrase, types in catalogue().lexicon.items():
        if " " not in phrase and len(phrase) >= MIN_FUZZY_CHARS:
            for d in _deletes(phrase):
                index.setdefault(d, set()).update(types)
    return {k: frozenset(v) for k, v in index.items()}


def named_types(text: str) -> frozenset[str]:
    """The AI2-THOR types an instruction names: every candidate of every lexicon phrase found by the rule
    parser's longest match (plurals folded; "lamp" names both lamps), plus one-edit misspellings of
    one-word names of five letters or more ("refrigerater", "tomatoe", "micowave")."""
    from models.language.rule_parser import RuleParser, words_of
    words = words_of(text)
    named = {t for m in RuleParser.shared().mentions(words) for t in m.types}
    for w in words:
        named.update(misspelt_types(w))
    return frozenset(named)


def misspelt_types(word: str) -> frozenset[str]:
    """The types a word names as a one-edit misspelling of a one-word name of five letters or more
    (empty for a lexicon word, a short word or a real word such as "place")."""
    from models.language.rule_parser import RuleParser
    if len(word) < MIN_FUZZY_CHARS or word in NOT_MISSPELLINGS or word in RuleParser.shared().lexicon:
        return frozenset()
    index = _fuzzy_index()
    return frozenset(t for d in _deletes(word) for t in index.get(d, ()))


@cache
def load_annotations(split: str | None = None) -> tuple[Annotation, ...]:
    """ALFRED rows of one split (train, valid_seen, valid_unseen), or all of them."""
    raw = resources.files("models").joinpath("data/alfred_annotations.jsonl.gz").read_bytes()
    rows = [json.loads(line) for line in gzip.decompress(raw).decode().splitlines() if line]
    return tuple(Annotation(split=r["split"], task_type=r["task_type"], instruction=r["task_desc"],
                            object_target=r["object_target"], parent_target=r["parent_target"],
                            toggle_target=r["toggle_target"], sliced=r["object_sliced"], floor_plan=r["floor_plan"])
                 for r in rows if split is None or r["split"] == split)
