"""decision.md's gate: Plan2Place and greedy with the old `first_ids` (placed objects with a broken constraint) and the
new one (objects left out for want of room too) on fresh plans (tag `left-out-broken`: 48 `seen`, `unseen_a`, `unseen_b`
x 2 seeds, 24 `dense` x 1 seed; `human`: the 80 iTHOR rooms off the bench's sample and the diagnosis plans, 1 seed),
alternating in one process; writes `runs.json` and `result.md` here:

    PYTHONPATH=. python app/bench/results/plan2place/left-out-broken/gate.py
"""
import json
import sys
from pathlib import Path

from app.bench.paired import alternating, header, store, variant_rows
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans
from models.placement import reorder
from models.placement.result import NO_ROOM

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "broken-first"))
from diagnose import METRICS, p50s  # noqa: E402

TAG = "left-out-broken"
PLACERS = ("plan2place", "greedy")
VARIANTS = ("placed only", "left out too")


def placed_only(ep) -> list[str]:
    """`reorder.first_ids` as shipped: the placed objects with a broken constraint and their relations' targets."""
    objects, ids = ep.problem.constraints.objects, set(reorder.broken(ep))
    ids |= {c.target for oid in list(ids) for c in objects[oid].relations}
    return [o.id for o in ep.problem.plan.objects if o.id in ids and o.id not in ep.problem.fixed]


def left_out_too(ep) -> list[str]:
    """The variant (not shipped): the objects left out for want of room count as broken too."""
    objects = ep.problem.constraints.objects
    ids = set(reorder.broken(ep)) | {oid for oid, why in ep.failed.items() if why == NO_ROOM}
    ids |= {c.target for oid in list(ids) if oid in objects for c in objects[oid].relations}
    return [o.id for o in ep.problem.plan.objects if o.id in ids and o.id not in ep.problem.fixed]


def human_rooms() -> list:
    """The 80 iTHOR rooms off the placement bench's sample (index % 6 == 0) and the diagnosis plans (3)."""
    return [r.plan for i, r in enumerate(load_dataset("human")) if i % 6 in (1, 2, 4, 5)]


def run() -> list[dict]:
    plan_sets = {**{ds: (fresh_plans(ds, TAG, 48), range(2)) for ds in ("seen", "unseen_a", "unseen_b")},
                 "dense": (fresh_plans("dense", TAG, 24), range(1)), "human": (human_rooms(), range(1))}
    return alternating(plan_sets, reorder, "first_ids", dict(zip(VARIANTS, (placed_only, left_out_too))),
                       METRICS, PLACERS)


def changed(rows: list[dict]) -> list[str]:
    """The runs whose layout differs between the two variants."""
    by = {}
    for r in rows:
        by.setdefault((r["set"], r["placer"], r["plan"], r["seed"]), {})[r["solver"]] = r
    return [f"- {s} / {placer}: {plan} seed {seed}: " + ", ".join(
            f"{m} {pair[VARIANTS[1]][m] - pair[VARIANTS[0]][m]:+.3f}" for m, *_ in METRICS[:5]
            if pair[VARIANTS[0]][m] is not None and pair[VARIANTS[1]][m] is not None)
            for (s, placer, plan, seed), pair in by.items() if pair[VARIANTS[0]]["layout"] != pair[VARIANTS[1]]["layout"]]


def report(rows: list[dict]) -> str:
    moved = changed(rows)
    return "\n".join(["left out too - placed only: the difference, mean over the same (plan, seed) runs [95 % bootstrap "
                      "interval over plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating in "
                      "one process); **bold** = better with the interval clear of 0, _italic_ = worse.", "",
                      *header("set / placer", METRICS), *variant_rows(rows, *VARIANTS, METRICS, PLACERS), "",
                      f"Layouts changed: {len(moved)} (new - old, metrics as fractions)", "", *moved, "",
                      "PTO p50 per object (ms), placed only -> left out too:", "", *p50s(rows, PLACERS, VARIANTS)]) + "\n"


if __name__ == "__main__":
    runs = run()
    (HERE / "runs.json").write_text(json.dumps(runs))  # kept before the report is made
    store(HERE, runs, report(runs))
