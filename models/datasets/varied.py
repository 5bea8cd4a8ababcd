"""Training plans in rooms of varied size and density for Plan2Place (`h3ds train placement --dataset varied`).

The `seen` set plans every instruction with one generator setting, so a placer trained on it sees one room
size and one density only, and measured no gain on the sets built with other settings (`unseen_a`: smaller
rooms, more objects; `unseen_b`: larger rooms, sparser; issue 8). Here the same training instructions (the
`seen` training split, nothing else: no evaluation set shares an instruction with these plans) are replanned
for each episode with generator settings and LLM habits drawn at random from ranges wide enough to cover
those sets. This is domain randomisation: the evaluation sets' instructions stay unseen, their generator
ranges do not, and the README says so.

A plan is a pure function of (seed, episode), so a resumed run sees the plans it would have seen.
"""

from __future__ import annotations

import random
from functools import cache

from models.datasets.constraint_sets import load_dataset
from models.datasets.llm_style import Habits, restyle
from models.language.alfred import load_annotations
from models.planning import ConstraintWriter, RoomPlanner, RoomPlannerSettings
from models.values import ConstraintPlan, TaskGraph
from models.world import ROOM_TYPES

NAME = "varied"


@cache
def graphs_of(split: str) -> tuple[TaskGraph, ...]:
    """The ALFRED task graphs of the instructions in a split of `seen` (train or validation), in a fixed order."""
    wanted = {r.instruction for r in load_dataset("seen", split)}
    graphs = {row.instruction: row.task_graph() for row in load_annotations("train") if row.instruction in wanted}
    return tuple(graphs[i] for i in sorted(graphs))


def random_settings(rng: random.Random) -> tuple[RoomPlannerSettings, Habits]:
    low = rng.randint(2, 6)
    settings = RoomPlannerSettings(min_context=low, max_context=rng.randint(low + 4, 16),
                                   size_scale=rng.uniform(0.8, 1.25), surface_items=rng.uniform(0.3, 0.7),
                                   group_chance=rng.uniform(0.4, 0.9), as_stored=True)  # as the stored sets
    rate = lambda: rng.uniform(0.0, 0.3)  # noqa: E731
    habits = Habits(rename=rate(), misspell=rate() / 3, id_respell=rate() / 2, missing_target=rate() / 5,
                    self_target=rate() / 6, drop_line=rate() / 4, drop_relation=rate() * 1.5,
                    extra_relation=rate())
    return settings, habits


def varied_plan(seed: int, episode: int, split: str = "train") -> ConstraintPlan:
    """The plan of `episode`: an instruction of the split in a random room type and random settings (the
    validation split: for choosing among checkpoints on plans no benchmark uses)."""
    rng = random.Random(f"{NAME}-{split}-{seed}-{episode}")
    graphs = graphs_of(split)
    graph = graphs[rng.randrange(len(graphs))]
    settings, habits = random_settings(rng)
    room = rng.choice(ROOM_TYPES)
    room_plan = RoomPlanner(settings).plan(graph.model_copy(update={"room_type": room}),
                                           seed=rng.randrange(2**31), plan_id=f"{NAME}-{split}-{seed}-{episode:06d}")
    plan = ConstraintWriter().write(room_plan)
    text = restyle(plan.constraints, [o.id for o in plan.objects], rng, habits)
    return plan.model_copy(update={"constraints": text})
