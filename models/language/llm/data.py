"""Training examples for f_theta1: ALFRED instructions with their compact task graphs.

Until the project's language splits land (models/datasets/language_sets.py), the training set is
ALFRED `train` minus every instruction whose text (case and spacing folded) also occurs in
`valid_seen` or `valid_unseen`, so no evaluation sentence is ever trained on.
"""

from __future__ import annotations

from models.language.alfred import load_annotations
from models.language.llm.graph_text import fields_of
from models.language.llm.train import Example


def _key(text: str) -> str:
    return " ".join(text.lower().split())


def training_examples() -> list[Example]:
    held_out = {_key(a.instruction) for s in ("valid_seen", "valid_unseen") for a in load_annotations(s)}
    return [Example(a.instruction, a.room_type, fields_of(a)) for a in load_annotations("train")
            if _key(a.instruction) not in held_out]
