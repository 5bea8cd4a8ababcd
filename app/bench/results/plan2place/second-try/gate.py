"""decision.md's gate: Plan2Place as shipped and with `variant.place_twice` on fresh plans (tag `second-try`: 48
`dense` x 5 seeds, 24 per other set x 2 seeds; `human`: the earlier gates' 24 rooms x 2 seeds), alternating in one
process; writes `runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/second-try/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, variant_report
from app.bench.paired import alternating, store
from models.placement.plan2place import solver
from variant import SHIPPED, place_twice

HERE = Path(__file__).parent
VARIANTS = ("shipped", "second try")
PLACERS = ("plan2place",)

if __name__ == "__main__":
    runs = alternating(fresh_sets("second-try"), solver, "place", dict(zip(VARIANTS, (SHIPPED, place_twice))), METRICS,
                       PLACERS)
    store(HERE, runs, variant_report("second try", "fresh plans", runs, VARIANTS, PLACERS))
