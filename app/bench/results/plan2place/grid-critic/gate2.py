"""decision.md's gate 2: the shipped Plan2Place with and without the floor critic (fit.py's chosen weights) on fresh
plans (tag `grid-critic`, 24 per set, 2 seeds; `human`: `human_plans`), alternating in one process; writes `runs.json` and `result.md` here. (It first ran with the critic's step as a
hook in `policy.place`; moved here when the gate failed, the same 240 layouts per variant were made again.)

    PYTHONPATH=. python app/bench/results/plan2place/grid-critic/gate2.py CRITIC.pt
"""
import sys
from pathlib import Path

import torch

from app.bench.paired import alternating, header, store, variant_rows
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans
import models.placement.plan2place.solver as solver
from models.placement.plan2place.policy import place

sys.path.insert(0, str(Path(__file__).parent))
from floor import FloorCritic, place_with_floor  # noqa: E402

HERE = Path(__file__).parent
TAG = "grid-critic"
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2), ("cnt", 100, True, 2),
           ("key_nav", 100, True, 2), ("realism", 100, True, 2), ("pto_ms", 1, False, 2))


def human_plans() -> list:
    """The iTHOR rooms have no fresh recipe: 24 of those off the placement bench's sample (every sixth room from the
    first) and off the diagnosis plans (every sixth from the fourth)."""
    return [r.plan for i, r in enumerate(load_dataset("human")) if i % 6 in (1, 4)][:24]


def run(critic: FloorCritic) -> list[dict]:
    plan_sets = {ds: (fresh_plans(ds, TAG, 24) if ds != "human" else human_plans(), range(2)) for ds in SETS}
    return alternating(plan_sets, solver, "place", {"shipped": place, "floor critic": place_with_floor(critic)},
                       METRICS, placers=("plan2place",))


def report(rows: list[dict]) -> str:
    lines = ["floor critic - shipped: the difference, mean over the same (plan, seed) runs [95 % bootstrap interval "
             "over plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating in one process); "
             "**bold** = better with the interval clear of 0, _italic_ = worse.", "",
             *header("set / placer", METRICS),
             *variant_rows(rows, "shipped", "floor critic", METRICS, placers=("plan2place",))]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    arrays = {k: v.numpy() for k, v in torch.load(sys.argv[1]).items()}
    runs = run(FloorCritic(arrays))
    store(HERE, runs, report(runs))
