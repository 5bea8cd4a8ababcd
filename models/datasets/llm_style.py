"""Phrasing habits of LLM-written constraint text, applied to clean plans to make the unseen sets.

Real LLM output renames constraints ("next to"), misspells them ("infront of"), changes case and
spacing, spells ids differently ("Fridge_0"), points at objects that do not exist, points objects at
themselves, and forgets lines. Each habit is applied with a seeded probability; the reader must cope
with all of them (constraints.md's reading rules).
"""

from __future__ import annotations

import random
from dataclasses import dataclass

RENAMES = {"near": ["next to", "close to", "Near", "nearby"], "in front of": ["infront of", "in front", "front of"],
           "face to": ["facing", "faces", "face"], "side of": ["beside", "on the side of"],
           "center aligned": ["centre aligned", "aligned"], "far": ["away from", "Far"],
           "around": ["surrounding"], "left of": ["to the left of"], "right of": ["to the right of"]}
GLOBAL_RENAMES = {"edge": ["wall", "against wall", "Edge"], "middle": ["center", "centre", "Middle"]}
MISSPELL = {"near": "naer", "face to": "fac to", "in front of": "in fornt of", "side of": "sid of",
            "around": "arond", "far": "farr"}


@dataclass(frozen=True)
class Habits:
    rename: float = 0.0
    misspell: float = 0.0
    id_respell: float = 0.0
    missing_target: float = 0.0
    self_target: float = 0.0
    drop_line: float = 0.0
    drop_relation: float = 0.0
    extra_relation: float = 0.0


def restyle(text: str, ids: list[str], rng: random.Random, habits: Habits) -> str:
    lines = []
    for line in text.splitlines():
        fields = [f.strip() for f in line.split("|")]
        oid, placement, relations = fields[0], fields[1], fields[2:]
        if rng.random() < habits.drop_line:
            continue
        if rng.random() < habits.id_respell:
            oid = oid.replace("-", "_").capitalize()
        if rng.random() < habits.rename:
            placement = rng.choice(GLOBAL_RENAMES[placement])
        out = []
        for rel in relations:
            name, _, target = (p.strip() for p in rel.partition(","))
            if rng.random() < habits.drop_relation:
                continue
            if rng.random() < habits.misspell and name in MISSPELL:
                name = MISSPELL[name]
            elif rng.random() < habits.rename and name in RENAMES:
                name = rng.choice(RENAMES[name])
            if rng.random() < habits.missing_target:
                target = f"{target.rsplit('-', 1)[0]}-{rng.randint(5, 9)}"
            out.append(f"{name}, {target}")
        if rng.random() < habits.extra_relation and len(ids) > 1:
            other = rng.choice([i for i in ids if i != fields[0]])
            out.append(f"{rng.choice(['near', 'face to', 'far', 'side of'])}, {other}")
        if rng.random() < habits.self_target:
            out.append(f"near, {fields[0]}")
        lines.append(" | ".join([oid, placement, *out]))
    return "\n".join(lines)
