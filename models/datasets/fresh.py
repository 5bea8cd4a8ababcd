"""Plans no benchmark or experiment has placed, for judging a change after it was chosen on other plans: each set's
own recipe (room planner settings, constraint writer, LLM habits) with a seed of its own (`tag`), on instructions the
set holds out of training (`seen`: its validation instructions; the unseen sets: theirs); `dense`: such `seen` plans
densified by the `dense` recipe. `human` has none: its 120 iTHOR rooms are all in use.

A `tag` once used to judge something is spent; use a new one for the next decision.
"""

from __future__ import annotations

import random

from models.datasets.constraint_sets import DATASETS, SEED, PlanRecord, load_dataset
from models.datasets.hard_sets import densify
from models.datasets.llm_style import restyle
from models.language.alfred import load_annotations
from models.planning import ConstraintWriter, RoomPlanner
from models.values import ConstraintPlan
from models.world import ROOM_TYPES

SEEN_PER_DENSE = 80 / 24  # `seen` plans built per `dense` plan asked (densify gives up on some)


def _built(name: str, tag: str, n: int) -> list[PlanRecord]:
    recipe, rng = DATASETS[name], random.Random(f"{SEED}-{tag}-{name}")
    held = {r.instruction for r in load_dataset(name, "validation" if name == "seen" else None)}
    rows = sorted({r.instruction: r for r in load_annotations(recipe.split) if r.instruction in held}.items())
    rng.shuffle(rows)
    planner, writer, out = RoomPlanner(recipe.settings), ConstraintWriter(), []
    for k, (instruction, row) in enumerate(rows[:n]):
        room = ROOM_TYPES[rng.randrange(len(ROOM_TYPES))]
        plan = writer.write(planner.plan(row.task_graph().model_copy(update={"room_type": room}),
                                         seed=rng.randrange(2**31), plan_id=f"{name}-{tag}-{k:03d}"))
        text = restyle(plan.constraints, [o.id for o in plan.objects], rng, recipe.habits)
        out.append(PlanRecord("fresh", instruction, plan.model_copy(update={"constraints": text})))
    return out


def fresh_records(name: str, tag: str, n: int = 24) -> list[PlanRecord]:
    """`n` new plans of the set `name` (seen, unseen_a, unseen_b, dense) with their instructions (split "fresh"),
    the same for the same `tag`."""
    if name == "dense":
        rng = random.Random(f"{SEED}-{tag}-dense")
        made = ((r, densify(r.plan, rng)) for r in _built("seen", tag, round(n * SEEN_PER_DENSE)))
        return [PlanRecord("fresh", r.instruction, plan) for r, plan in made if plan is not None][:n]
    if name not in DATASETS:
        raise ValueError(f"no fresh plans for {name!r}: only {', '.join([*DATASETS, 'dense'])}")
    return _built(name, tag, n)


def fresh_plans(name: str, tag: str, n: int = 24) -> list[ConstraintPlan]:
    """The plans of `fresh_records`."""
    return [r.plan for r in fresh_records(name, tag, n)]
