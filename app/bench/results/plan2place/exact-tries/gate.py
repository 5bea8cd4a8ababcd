"""decision.md's gate: Plan2Place and greedy with the exact finish solving once (`TRIES = 1`) and up to three times
(`TRIES = 3`, the next seed where Z3's layout is not kept), on fresh plans (tag `exact-tries`: 48 `dense` x 5 seeds,
24 per other set x 2 seeds; `human`: the earlier gates' 24 rooms x 2 seeds), alternating in one process; writes
`runs.json` and `result.md` here, the rule's pooled constraints figure last:

    PYTHONPATH=. python app/bench/results/plan2place/exact-tries/gate.py

It ran at 5ed8427, where `exact_finish.TRIES` existed; the gate failed and `TRIES` was removed, so run it from there.
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, pooled_constraints, variant_report
from app.bench.paired import alternating, store
from models.placement import exact_finish

HERE = Path(__file__).parent
VARIANTS = {"one solve": 1, "three tries": 3}
PLACERS = ("plan2place", "greedy")


if __name__ == "__main__":
    runs = alternating(fresh_sets("exact-tries"), exact_finish, "TRIES", VARIANTS, METRICS, PLACERS)
    report = variant_report("the exact finish's three tries", "fresh plans", runs, tuple(VARIANTS), PLACERS)
    store(HERE, runs, report + "\nConstraints met (x 100), three tries minus one, the five sets pooled:\n\n"
          + "\n".join(pooled_constraints(runs, p, VARIANTS) for p in PLACERS) + "\n")
