"""Training examples for f_theta1: ALFRED instructions with their compact task graphs.

- `training_examples`: ALFRED `train` minus every instruction whose text (case and spacing folded) also
  occurs in `valid_seen` or `valid_unseen`, so no evaluation sentence is ever trained on;
- `augmented_examples` (`h3ds train language --augment`): rows a model already trained on, each as it is
  plus its object-shift version (targets from the training pool of rare types only) and its text-shift
  version, made with a training seed of their own, so the model learns to copy the named object.
"""

from __future__ import annotations

from models.datasets.language_sets import text_key
from models.language.alfred import load_annotations
from models.language.llm.graph_text import fields_of
from models.language.llm.train import Example

AUGMENT_SEED = 21  # of the augmentation's TS / OS rewrites: not the evaluation sets' (10), confirmation (11) or dev (13)


def training_examples(skip_scenes: frozenset[str] = frozenset()) -> list[Example]:
    """ALFRED `train` less the evaluation texts and the annotations of `skip_scenes` (floor plans held
    out to measure a model on scenes it never saw)."""
    held_out = {text_key(a.instruction) for s in ("valid_seen", "valid_unseen") for a in load_annotations(s)}
    return [Example(a.instruction, a.room_type, fields_of(a)) for a in load_annotations("train")
            if text_key(a.instruction) not in held_out and a.floor_plan not in skip_scenes]


def augmented_examples(trained: list, kept_apart: set[str], seed: int = AUGMENT_SEED) -> list[Example]:
    """`trained` (LabelledInstruction rows the model already trained on) as they are, plus their
    `object_shift` versions over the training pool of `rare_target_pools()` and their `text_shift`
    versions, both with `seed` (labels re-derived by those procedures). Any row whose text (case and
    spacing folded) is in `kept_apart` (rows that must stay unseen: policy, confirmation, evaluation)
    is left out, and so are the rewrites of such a row."""
    from models.language.combined import rule_fields  # the compact fields of any labelled graph
    from models.datasets.language_sets import object_shift, rare_target_pools, text_shift
    rows = [r for r in trained if text_key(r.instruction) not in kept_apart]
    pool, _ = rare_target_pools()
    out = rows + object_shift(rows, seed, pool) + text_shift(rows, seed)
    return [Example(r.instruction, r.room_type, rule_fields(r.label)) for r in out
            if text_key(r.instruction) not in kept_apart]
