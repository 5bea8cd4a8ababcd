"""decision.md's gate: Plan2Place and greedy with and without going back when an object finds no room
(models.placement.backtrack; without: `DEPTH` 0) on fresh plans (tag `backtrack`: 48 `dense` x 5 seeds, 24 per other
set x 2 seeds; `human`: the group-moves gate's 24 rooms x 2 seeds), alternating in one process; writes `runs.json`
and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/backtrack/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, variant_report
from app.bench.paired import alternating, store
from models.placement import backtrack

HERE = Path(__file__).parent
VARIANTS = ("without", "backtrack")
PLACERS = ("plan2place", "greedy")

if __name__ == "__main__":
    runs = alternating(fresh_sets("backtrack"), backtrack, "DEPTH", dict(zip(VARIANTS, (0, backtrack.DEPTH))), METRICS,
                       PLACERS)
    store(HERE, runs, variant_report(f"backtrack (DEPTH {backtrack.DEPTH}, TRIES {backtrack.TRIES})", "fresh plans",
                                     runs, VARIANTS, PLACERS))
