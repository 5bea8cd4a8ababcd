"""decision.md's gate: Plan2Place and greedy without Z3's window in larger rooms (`ONE_MORE_AT = 0`) and with it where
one constraint stays broken (`1`), on fresh plans (tag `one-more`: 48 `dense` x 5 seeds, 24 per other set x 2 seeds;
`human`: the earlier gates' 24 rooms x 2 seeds), alternating in one process; writes `runs.json` and `result.md` here,
the rule's pooled constraints figure last:

    PYTHONPATH=. python app/bench/results/plan2place/one-more/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, pooled_constraints, variant_report
from app.bench.paired import alternating, store
from models.placement import exact_finish

HERE = Path(__file__).parent
VARIANTS = {"without": 0, "one broken": 1}
PLACERS = ("plan2place", "greedy")


if __name__ == "__main__":
    runs = alternating(fresh_sets("one-more"), exact_finish, "ONE_MORE_AT", VARIANTS, METRICS, PLACERS)
    report = variant_report("Z3's window where one constraint stays broken", "fresh plans", runs, tuple(VARIANTS),
                            PLACERS)
    store(HERE, runs, report + "\nConstraints met (x 100), with minus without, the five sets pooled:\n\n"
          + "\n".join(pooled_constraints(runs, p, VARIANTS) for p in PLACERS) + "\n")
