"""A second polish round in crowded rooms (the variant) against one round, Plan2Place and greedy, on the plans
`decision.md` names, the order alternating from run to run in one process; writes `runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/second-round/run.py

It ran on the code before the change it decided, with `polish` as one round and the second added here; the variants
are now written against the code as it is (`polish` runs the second round itself), with the same two behaviours.
"""
from pathlib import Path

import models.placement.polish as polish
import models.placement.repair as repair
from app.bench.paired import alternating, header, store, variant_rows
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans
from models.placement.polish import crowded

HERE = Path(__file__).parent
TAG = "second-round"
METRICS = (("constraint_satisfaction", 100, True, 2), ("cnt", 100, True, 2), ("key_nav", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3), ("pto_ms", 1, False, 2))


def one_round(ep, observer=None):
    moved = []
    polish._round(ep, observer, moved, {})
    return moved


VARIANTS = {"one round": one_round, "two in crowded rooms": polish.polish}  # the second: the code as it is now


def plan_sets() -> dict[str, tuple[list, range]]:
    human = [r.plan for r in load_dataset("human") if crowded(r.plan)]
    others = {ds: [r.plan for i, r in enumerate(load_dataset(ds, "validation" if ds == "seen" else None))
                   if i % 25 == 11][:8] for ds in ("seen", "unseen_a")}
    return {"dense (fresh)": (fresh_plans("dense", TAG, 48), range(5)), "human (crowded)": (human, range(5)),
            **{f"{ds} (identity check)": (plans, range(2)) for ds, plans in others.items()}}


def run() -> list[dict]:
    return alternating(plan_sets(), repair, "polish", VARIANTS, METRICS)


def report(rows: list[dict]) -> str:
    old, new = VARIANTS
    lines = [f"{old} -> {new}: the difference, mean over the same (plan, seed) runs [95 % bootstrap interval over "
             "plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating in one process); "
             "**bold** = better with the interval clear of 0, _italic_ = worse.", "", *header("set / placer", METRICS),
             *variant_rows(rows, old, new, METRICS)]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    runs = run()
    store(HERE, runs, report(runs))
