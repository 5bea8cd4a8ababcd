"""decision.md's gate: Plan2Place and greedy without the exact finish (`MAX_OBJECTS = 0`) and with it as the repairs
run it (`MIN_MET`), on fresh plans (tag `exact-default`: 48 `dense` x 5 seeds, 24 per other set x 2 seeds; `human`:
the earlier gates' 24 rooms x 2 seeds), alternating in one process; writes `runs.json` and `result.md` here, the rule's
pooled constraints figure last:

    PYTHONPATH=. python app/bench/results/plan2place/exact-default/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, pooled_constraints, variant_report
from app.bench.paired import alternating, store
from models.placement import exact_finish

HERE = Path(__file__).parent
VARIANTS = {"without": 0, "exact finish": exact_finish.MAX_OBJECTS}
PLACERS = ("plan2place", "greedy")


if __name__ == "__main__":
    runs = alternating(fresh_sets("exact-default"), exact_finish, "MAX_OBJECTS", VARIANTS, METRICS, PLACERS)
    report = variant_report("the exact finish in the repairs", "fresh plans", runs, tuple(VARIANTS), PLACERS)
    store(HERE, runs, report + "\nConstraints met (x 100), with minus without, the five sets pooled:\n\n"
          + "\n".join(pooled_constraints(runs, p, VARIANTS) for p in PLACERS) + "\n")
