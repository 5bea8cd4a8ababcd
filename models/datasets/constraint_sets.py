"""Constraint datasets built from ALFRED instructions and the room planner (no LLM can run here at scale).

- `seen`     ALFRED train instructions x the nine room types (6,102 plans, about 5,200 train, the
             rest validation, split by instruction: no validation instruction appears in training);
             rooms of the usual sizes, 3-14 context objects, clean Holodeck text.
- `unseen_a` ALFRED valid_unseen instructions, one room type each (518 plans); smaller rooms, more
             objects, denser constraints, and LLM habits: renamed and misspelled constraints, ids
             pointing at missing objects.
- `unseen_b` ALFRED valid_seen instructions, two room types each (938 plans); larger rooms, sparser
             constraints, other habits: respelled ids, renamed globals, self-references, lost lines.

Deterministic for the fixed seed: `h3ds data build` rewrites `models/data/datasets/*.jsonl.gz`, and a
test checks the stored files against a rebuild.
"""

from __future__ import annotations

import gzip
import hashlib
import json
import random
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from models.datasets.llm_style import Habits, restyle
from models.language.alfred import load_annotations
from models.planning import ConstraintWriter, RoomPlanner, RoomPlannerSettings
from models.values import ConstraintPlan, Layout
from models.world import ROOM_TYPES

SEED = 20260101
OUT = Path(__file__).resolve().parent.parent / "data" / "datasets"


@dataclass(frozen=True)
class Recipe:
    split: str  # ALFRED split the instructions come from
    n_instructions: int
    rooms_per_instruction: int
    settings: RoomPlannerSettings
    habits: Habits
    n_train: int = 0


# The stored sets were built before the room planner gave every room its defining furniture (`defining`) and drew
# each type as often as iTHOR rooms hold it; they are rebuilt as they were (`as_stored`), so that every stored run and
# the trained weights stay comparable with them.
DATASETS: dict[str, Recipe] = {
    "seen": Recipe("train", 678, 9, RoomPlannerSettings(min_context=3, max_context=14, surface_items=0.5,
                                                        as_stored=True),
                   Habits(), n_train=5200),
    "unseen_a": Recipe("valid_unseen", 518, 1, RoomPlannerSettings(min_context=5, max_context=16, size_scale=0.85,
                                                                as_stored=True),
                       Habits(rename=0.25, misspell=0.1, missing_target=0.06, extra_relation=0.35)),
    "unseen_b": Recipe("valid_seen", 469, 2, RoomPlannerSettings(min_context=2, max_context=10, size_scale=1.2,
                                                                 group_chance=0.5, as_stored=True),
                       Habits(rename=0.3, id_respell=0.15, self_target=0.05, drop_line=0.08, drop_relation=0.5)),
}


HARD_SETS = ("dense", "human")  # models.datasets.hard_sets
ALL_SETS = (*DATASETS, *HARD_SETS)


@dataclass(frozen=True)
class PlanRecord:
    split: str  # train / validation (seen) or test (unseen sets)
    instruction: str
    plan: ConstraintPlan
    reference: Layout | None = None  # the arrangement people made (`human` set only)


def _rows(recipe: Recipe, rng: random.Random):
    """Instructions with their ground-truth task graphs (from ALFRED's labels, not from a parser, so that
    the datasets do not change when a parser improves)."""
    rows = list(load_annotations(recipe.split))
    rng.shuffle(rows)
    for row in rows[:recipe.n_instructions]:
        yield row.instruction, row.task_graph()


def build_dataset(name: str) -> list[PlanRecord]:
    if name in HARD_SETS:
        from models.datasets import hard_sets
        if name == "human":
            return hard_sets.build_human()
        return hard_sets.build_dense([r for r in build_dataset("seen") if r.split == "validation"])
    recipe = DATASETS[name]
    rng = random.Random(f"{SEED}-{name}")
    planner, writer = RoomPlanner(recipe.settings), ConstraintWriter()
    records = []
    for n_instr, (instruction, graph) in enumerate(_rows(recipe, rng)):
        rooms = ROOM_TYPES if recipe.rooms_per_instruction == len(ROOM_TYPES) else \
            [ROOM_TYPES[(n_instr + k * 4) % len(ROOM_TYPES)] for k in range(recipe.rooms_per_instruction)]
        for room in rooms:
            pid = f"{name}-{len(records):05d}"
            room_plan = planner.plan(graph.model_copy(update={"room_type": room}), seed=rng.randrange(2**31),
                                     plan_id=pid)
            plan = writer.write(room_plan)
            text = restyle(plan.constraints, [o.id for o in plan.objects], rng, recipe.habits)
            plan = plan.model_copy(update={"constraints": text})
            records.append(PlanRecord("", instruction, plan))
    # split by instruction, not by plan: no validation instruction is seen in training in any room type
    instructions = sorted({r.instruction for r in records})
    random.Random(f"{SEED}-{name}-split").shuffle(instructions)
    train, count = set(), 0
    for instruction in instructions:
        if count >= recipe.n_train:
            break
        train.add(instruction)
        count += sum(r.instruction == instruction for r in records)
    default = "test" if recipe.n_train == 0 else "validation"
    return [PlanRecord("train" if r.instruction in train else default, r.instruction, r.plan) for r in records]


def encode(records: list[PlanRecord]) -> bytes:
    lines = [json.dumps({"split": r.split, "instruction": r.instruction,
                         "plan": r.plan.model_dump(mode="json", exclude_none=True),
                         **({"reference": r.reference.model_dump(mode="json", exclude_none=True)} if r.reference else {})},
                        sort_keys=True)
             for r in records]
    return gzip.compress(("\n".join(lines) + "\n").encode(), mtime=0)


def dataset_path(name: str) -> Path:
    return OUT / f"{name}.jsonl.gz"


def write_dataset(name: str) -> tuple[Path, str]:
    OUT.mkdir(parents=True, exist_ok=True)
    data = encode(build_dataset(name))
    dataset_path(name).write_bytes(data)
    return dataset_path(name), hashlib.sha256(gzip.decompress(data)).hexdigest()


def load_dataset(name: str, split: str | None = None) -> list[PlanRecord]:
    if name not in ALL_SETS:
        raise ValueError(f"unknown dataset {name!r}; available: {', '.join(ALL_SETS)}")
    raw = resources.files("models").joinpath(f"data/datasets/{name}.jsonl.gz").read_bytes()
    out = []
    for line in gzip.decompress(raw).decode().splitlines():
        row = json.loads(line)
        if split is None or row["split"] == split:
            ref = Layout.model_validate(row["reference"]) if "reference" in row else None
            out.append(PlanRecord(row["split"], row["instruction"], ConstraintPlan.model_validate(row["plan"]), ref))
    return out
