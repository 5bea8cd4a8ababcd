"""The constraint vocabulary of `constraints.md` as typed values, and how misspelled names are read."""

from __future__ import annotations

import difflib
from dataclasses import dataclass, field

GLOBALS: tuple[str, ...] = ("edge", "middle")
RELATIONS: tuple[str, ...] = ("near", "far", "in front of", "behind", "side of", "left of", "right of",
                              "around", "face to", "face same as", "center aligned")

# Relations whose point is to stand in the target's front zone: exempt from front-clearance rules.
FRONT_RELATIONS = {"in front of", "around", "behind", "side of", "left of", "right of"}

# Phrases real LLM output uses for a vocabulary name (read with a warning, like any misspelling).
ALIASES: dict[str, str] = {
    "next to": "near", "close to": "near", "beside": "side of", "by": "near", "adjacent to": "near",
    "nearby": "near", "away from": "far", "facing": "face to", "face": "face to", "faces": "face to",
    "facing towards": "face to", "face towards": "face to", "infront of": "in front of", "in front": "in front of",
    "front of": "in front of", "behind of": "behind", "back of": "behind", "centre aligned": "center aligned",
    "aligned": "center aligned", "center-aligned": "center aligned", "left": "left of", "right": "right of",
    "to the left of": "left of", "to the right of": "right of", "on the side of": "side of",
    "surround": "around", "surrounding": "around", "corner": "edge", "wall": "edge", "against wall": "edge",
    "center": "middle", "centre": "middle", "central": "middle", "face same": "face same as",
}


@dataclass(frozen=True)
class Constraint:
    """One relation of an object to a target (`target` is None for the globals edge / middle)."""

    name: str
    target: str | None = None

    def text(self) -> str:
        return self.name if self.target is None else f"{self.name}, {self.target}"


@dataclass
class ObjectConstraints:
    object_id: str
    placement: str  # "edge" or "middle"
    relations: list[Constraint] = field(default_factory=list)


@dataclass
class ConstraintSet:
    """Every object's constraints, plus the warnings raised while reading them."""

    objects: dict[str, ObjectConstraints]
    warnings: list[str] = field(default_factory=list)

    def relations(self) -> list[tuple[str, Constraint]]:
        return [(oid, c) for oid, oc in self.objects.items() for c in oc.relations]

    def count(self) -> int:
        return len(self.objects) + len(self.relations())

    def tied(self, a: str, b: str) -> bool:
        """Is one of a, b asked to stand in the other's front zone (a chair at a desk)?"""
        return any(c.target == b and c.name in FRONT_RELATIONS for c in self.objects[a].relations) or \
            any(c.target == a and c.name in FRONT_RELATIONS for c in self.objects[b].relations)


def resolve_name(raw: str, vocabulary: tuple[str, ...]) -> tuple[str | None, bool]:
    """(canonical name, exact?) for a written constraint name; None when nothing is close enough."""
    key = " ".join(raw.strip().lower().replace("_", " ").split())
    if key in vocabulary:
        return key, True
    alias = ALIASES.get(key)
    if alias in vocabulary:
        return alias, False
    close = difflib.get_close_matches(key, list(vocabulary) + list(ALIASES), n=1, cutoff=0.75)
    if close:
        name = close[0] if close[0] in vocabulary else ALIASES[close[0]]
        if name in vocabulary:
            return name, False
    return None, False
