"""decision2.md's plans that no one has placed (`models.datasets.fresh`, tag "fresh2"; `human`: iTHOR's rooms are all
in use, so 24 off the bench and the diagnosis plans, see decision2.md).

    PYTHONPATH=. python app/bench/results/plan2place/repair-reward/fresh2.py   # prints the plan counts and ids
"""

from __future__ import annotations

from functools import cache

from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans

N = 24


@cache
def fresh2(name: str) -> tuple:
    if name == "human":
        return tuple([r.plan for i, r in enumerate(load_dataset("human")) if i % 6 in (1, 2)][:N])
    return tuple(fresh_plans(name, "fresh2", N))


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
