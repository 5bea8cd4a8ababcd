"""decision.md's gate: Plan2Place with the group moves after the polish and without them (`groups.TRIES` 0) on fresh
plans (tag `group-moves`, 24 per set, 2 seeds; `human`: `human_plans`), alternating in one process; writes
`runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/group-moves/gate.py
"""
from pathlib import Path

from app.bench.gates import human_rooms as human_plans
from app.bench.paired import alternating, header, store, variant_rows
from models.datasets.fresh import fresh_plans
from models.placement import groups

HERE = Path(__file__).parent
TAG = "group-moves"
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2), ("cnt", 100, True, 2),
           ("key_nav", 100, True, 2), ("realism", 100, True, 2), ("pto_ms", 1, False, 2))


def run() -> list[dict]:
    plan_sets = {ds: (fresh_plans(ds, TAG, 24) if ds != "human" else human_plans(), range(2)) for ds in SETS}
    return alternating(plan_sets, groups, "TRIES", {"without": 0, "group moves": groups.TRIES}, METRICS,
                       placers=("plan2place",))


def report(rows: list[dict]) -> str:
    lines = ["group moves - without: the difference, mean over the same (plan, seed) runs [95 % bootstrap interval "
             "over plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating in one process); "
             "**bold** = better with the interval clear of 0, _italic_ = worse.", "",
             *header("set / placer", METRICS),
             *variant_rows(rows, "without", "group moves", METRICS, placers=("plan2place",))]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    runs = run()
    store(HERE, runs, report(runs))
