"""decision.md's gate: Plan2Place and greedy with and without solving again from another random state
(models.placement.restarts) on fresh plans (tag `restarts-two`: 48 `dense` x 5 seeds, 24 per other set x 2 seeds;
`human`: the earlier gates' 24 rooms x 2 seeds), alternating in one process; writes `runs.json` and `result.md` here.
The first gate (`first-gate/`) ran it with the tag `restarts`.

    PYTHONPATH=. python app/bench/results/plan2place/restarts/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, variant_report
from app.bench.paired import alternating, store
from diagnose import without
from models.placement import restarts

HERE = Path(__file__).parent
VARIANTS = ("without", "restarts")
PLACERS = ("plan2place", "greedy")

if __name__ == "__main__":
    runs = alternating(fresh_sets("restarts-two"), restarts, "restarted",
                       dict(zip(VARIANTS, (without, restarts.restarted))), METRICS, PLACERS)
    store(HERE, runs, variant_report("restarts", "fresh plans", runs, VARIANTS, PLACERS))
