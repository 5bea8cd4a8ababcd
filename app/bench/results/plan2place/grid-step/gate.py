"""decision.md's gate: Plan2Place and greedy with the shipped steps and with `variant.coarse_steps_off_crowded(0.15)`
on fresh plans (tag `grid-step`: 48 `dense` x 5 seeds, 24 per other set x 2 seeds; `human`: the earlier gates' 24
rooms x 2 seeds), alternating in one process; writes `runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/grid-step/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, variant_report
from app.bench.paired import alternating, store
from models.placement import greedy
from variant import coarse_steps_off_crowded

HERE = Path(__file__).parent
VARIANTS = ("shipped", "steps 0.15 m off crowded")
PLACERS = ("plan2place", "greedy")

if __name__ == "__main__":
    runs = alternating(fresh_sets("grid-step"), greedy, "_steps",
                       dict(zip(VARIANTS, (greedy._steps, coarse_steps_off_crowded(0.15)))), METRICS, PLACERS)
    store(HERE, runs, variant_report("steps 0.15 m off crowded", "fresh plans", runs, VARIANTS, PLACERS))
