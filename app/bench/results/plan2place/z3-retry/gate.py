"""decision.md's gate: Plan2Place and greedy with the exact finish solving a small room once (`TRIES = 1`) and up to
three times from other seeds (`3`), on fresh plans (tag `z3-retry`: 96 per generated set x 2 seeds, 48 `dense` x 5;
`human`: all 120 rooms at seeds 5 and 6), alternating in one process; writes `runs.json` and `result.md` here, the
rule's pooled constraints figure last:

    PYTHONPATH=. python app/bench/results/plan2place/z3-retry/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, SETS, pooled_constraints, variant_report
from app.bench.paired import alternating, store
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans
from models.placement import exact_finish

HERE = Path(__file__).parent
VARIANTS = {"once": 1, "three seeds": 3}
PLACERS = ("plan2place", "greedy")


def plan_sets() -> dict:
    """set -> (plans, seeds), as decision.md says."""
    return {ds: ([r.plan for r in load_dataset("human")], (5, 6)) if ds == "human" else
            (fresh_plans(ds, "z3-retry", 48), range(5)) if ds == "dense" else
            (fresh_plans(ds, "z3-retry", 96), range(2)) for ds in SETS}


if __name__ == "__main__":
    runs = alternating(plan_sets(), exact_finish, "TRIES", VARIANTS, METRICS, PLACERS)
    report = variant_report("Z3 asked again from other seeds in small rooms", "fresh plans", runs, tuple(VARIANTS),
                            PLACERS)
    store(HERE, runs, report + "\nConstraints met (x 100), three seeds minus once, the five sets pooled:\n\n"
          + "\n".join(pooled_constraints(runs, p, VARIANTS) for p in PLACERS) + "\n")
