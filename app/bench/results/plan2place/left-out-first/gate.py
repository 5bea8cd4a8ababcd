"""decision.md's gate: Plan2Place and greedy with and without solving again with the left-out objects first
(`again.ROUNDS` 0) on fresh plans (tag `left-out-first`: 48 `dense` x 5 seeds, 24 `seen`, `unseen_a`, `unseen_b` x 2
seeds; `human`: `human_rooms`, 1 seed), alternating in one process; writes `runs.json` and `result.md` here.

    git worktree add /tmp/lof e019e2f && cd /tmp/lof && PYTHONPATH=. python app/bench/results/plan2place/left-out-first/gate.py
"""
import json
import statistics
from pathlib import Path

from app.bench.paired import alternating, header, store, variant_rows
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans
from models.placement import again

HERE = Path(__file__).parent
TAG = "left-out-first"
METRICS = (("cnt", 100, True, 2), ("key_nav", 100, True, 2), ("constraint_satisfaction", 100, True, 2),
           ("energy", 1, False, 3), ("realism", 100, True, 2), ("pto_ms", 1, False, 2))
VARIANTS = ("without", "left out first")


def human_rooms() -> list:
    """The 80 iTHOR rooms off the placement bench's sample (index % 6 == 0) and the diagnosis plans (3)."""
    return [r.plan for i, r in enumerate(load_dataset("human")) if i % 6 in (1, 2, 4, 5)]


def run() -> list[dict]:
    plan_sets = {"dense": (fresh_plans("dense", TAG, 48), range(5)),
                 **{ds: (fresh_plans(ds, TAG, 24), range(2)) for ds in ("seen", "unseen_a", "unseen_b")},
                 "human": (human_rooms(), range(1))}
    return alternating(plan_sets, again, "ROUNDS", dict(zip(VARIANTS, (0, again.ROUNDS))), METRICS)


def report(rows: list[dict]) -> str:
    lines = ["left out first - without: the difference, mean over the same (plan, seed) runs [95 % bootstrap interval "
             "over plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating in one process); "
             "**bold** = better with the interval clear of 0, _italic_ = worse.", "",
             *header("set / placer", METRICS), *variant_rows(rows, *VARIANTS, METRICS), "",
             "PTO p50 per object (ms), without -> with:", ""]
    for label in dict.fromkeys(r["set"] for r in rows):
        for placer in ("plan2place", "greedy"):
            p50 = [statistics.median(r["pto_ms"] for r in rows if (r["set"], r["placer"], r["solver"]) ==
                                     (label, placer, v)) for v in VARIANTS]
            lines.append(f"- {label} / {placer}: {p50[0]:.2f} -> {p50[1]:.2f} ({100 * (p50[1] / p50[0] - 1):+.1f} %)")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    runs = run()
    (HERE / "runs.json").write_text(json.dumps(runs))  # kept before the report is made
    store(HERE, runs, report(runs))
