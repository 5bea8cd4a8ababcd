"""decision.md's gate: Plan2Place as shipped and with `variant.place_once_more` on fresh plans (tag `one-short`: 48
`dense` x 5 seeds, 24 per other set x 2 seeds; `human`: the earlier gates' 24 rooms x 2 seeds), alternating in one
process; writes `runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/one-short/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, variant_report
from app.bench.paired import alternating, store
from models.placement.plan2place import solver
from variant import SHIPPED, place_once_more

HERE = Path(__file__).parent
VARIANTS = ("shipped", "once more")
PLACERS = ("plan2place",)

if __name__ == "__main__":
    runs = alternating(fresh_sets("one-short"), solver, "place", dict(zip(VARIANTS, (SHIPPED, place_once_more))),
                       METRICS, PLACERS)
    store(HERE, runs, variant_report("once more", "fresh plans", runs, VARIANTS, PLACERS))
