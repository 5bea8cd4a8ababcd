"""decision2.md's plans that no one has placed: each set's own recipe with a new seed, on instructions the set holds
out of training (`human`: iTHOR's rooms are all in use; 24 off the bench and the diagnosis plans, see decision2.md).

    PYTHONPATH=. python app/bench/results/plan2place/repair-reward/fresh2.py   # prints the plan counts and ids
"""

from __future__ import annotations

import random
from functools import cache

from models.datasets import load_dataset
from models.datasets.constraint_sets import DATASETS, SEED
from models.datasets.hard_sets import densify
from models.datasets.llm_style import restyle
from models.language.alfred import load_annotations
from models.planning import ConstraintWriter, RoomPlanner
from models.world import ROOM_TYPES

N = 24
SEEN_FOR_DENSE = 80  # new `seen` plans to densify (densify gives up on some)


def _built(name: str, n: int) -> list:
    recipe, rng = DATASETS[name], random.Random(f"{SEED}-fresh2-{name}")
    held = {r.instruction for r in load_dataset(name, "validation" if name == "seen" else None)}
    rows = sorted({r.instruction: r for r in load_annotations(recipe.split) if r.instruction in held}.items())
    rng.shuffle(rows)
    planner, writer, out = RoomPlanner(recipe.settings), ConstraintWriter(), []
    for k, (_, row) in enumerate(rows[:n]):
        room = ROOM_TYPES[rng.randrange(len(ROOM_TYPES))]
        plan = writer.write(planner.plan(row.task_graph().model_copy(update={"room_type": room}),
                                         seed=rng.randrange(2**31), plan_id=f"{name}-fresh2-{k:03d}"))
        text = restyle(plan.constraints, [o.id for o in plan.objects], rng, recipe.habits)
        out.append(plan.model_copy(update={"constraints": text}))
    return out


@cache
def fresh2(name: str) -> tuple:
    if name == "dense":
        rng = random.Random(f"{SEED}-fresh2-dense")
        return tuple([p for p in (densify(s, rng) for s in _built("seen", SEEN_FOR_DENSE)) if p is not None][:N])
    if name == "human":
        return tuple([r.plan for i, r in enumerate(load_dataset("human")) if i % 6 in (1, 2)][:N])
    return tuple(_built(name, N))


if __name__ == "__main__":
    import sys
    sys.path.insert(0, __file__.rsplit("/", 2)[0] + "/lookahead-bound")
    from run import diagnosis_plans
    from app.bench.placement import pick_records
    for ds in ("seen", "unseen_a", "unseen_b", "dense", "human"):
        plans = fresh2(ds)
        used = {r.plan.id for n in (20, 40) for r in pick_records(ds, n)} | {p.id for p in diagnosis_plans(ds, 16)}
        print(ds, len(plans), "overlap with the bench or the diagnosis plans:", len(used & {p.id for p in plans}),
              [len(p.objects) for p in plans])
