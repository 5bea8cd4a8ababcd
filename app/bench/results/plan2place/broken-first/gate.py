"""decision.md's gate: Plan2Place and greedy with and without solving again with the objects of broken constraints
first (`reorder.ROUNDS` 0) on fresh plans (tag `broken-first`: 24 `seen`, `unseen_a`, `unseen_b` x 2 seeds, 24 `dense`
x 1 seed; `human`: the 80 iTHOR rooms off the bench's sample and the diagnosis plans, 1 seed), alternating in one
process; writes `runs.json` and `result.md` here:

    PYTHONPATH=. python app/bench/results/plan2place/broken-first/gate.py
"""
import json
import sys
from pathlib import Path

from app.bench.paired import alternating, header, store, variant_rows
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans
from models.placement import reorder

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
from diagnose import METRICS, VARIANTS, p50s  # noqa: E402

TAG = "broken-first"
PLACERS = ("plan2place", "greedy")


def human_rooms() -> list:
    """The 80 iTHOR rooms off the placement bench's sample (index % 6 == 0) and the diagnosis plans (3)."""
    return [r.plan for i, r in enumerate(load_dataset("human")) if i % 6 in (1, 2, 4, 5)]


def run() -> list[dict]:
    plan_sets = {**{ds: (fresh_plans(ds, TAG, 24), range(2)) for ds in ("seen", "unseen_a", "unseen_b")},
                 "dense": (fresh_plans("dense", TAG, 24), range(1)), "human": (human_rooms(), range(1))}
    return alternating(plan_sets, reorder, "ROUNDS", dict(zip(VARIANTS, (0, reorder.ROUNDS))), METRICS, PLACERS)


def report(rows: list[dict]) -> str:
    return "\n".join(["broken first - without: the difference, mean over the same (plan, seed) runs [95 % bootstrap "
                      "interval over plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating in "
                      "one process); **bold** = better with the interval clear of 0, _italic_ = worse.", "",
                      *header("set / placer", METRICS), *variant_rows(rows, *VARIANTS, METRICS, PLACERS), "",
                      "PTO p50 per object (ms), without -> with:", "", *p50s(rows, PLACERS, VARIANTS)]) + "\n"


if __name__ == "__main__":
    runs = run()
    (HERE / "runs.json").write_text(json.dumps(runs))  # kept before the report is made
    store(HERE, runs, report(runs))
