"""decision.md's gate: Plan2Place and greedy with and without the exact finish (models.placement.exact_finish) on
fresh plans (tag `exact-finish`: 48 `dense` x 5 seeds, 24 per other set x 2 seeds; `human`: the earlier gates' 24
rooms x 2 seeds), alternating in one process; writes `runs.json` and `result.md` here. It ran at commit 02f3fad,
where every step-wise placer finished this way; since then only `plan2place_exact` does (check that commit out to run
it again):

    PYTHONPATH=. python app/bench/results/plan2place/exact-finish/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, variant_report
from app.bench.paired import alternating, store
from models.placement import exact_finish

HERE = Path(__file__).parent
VARIANTS = {"without": 0, "exact finish": exact_finish.MAX_OBJECTS}
PLACERS = ("plan2place", "greedy")

if __name__ == "__main__":
    runs = alternating(fresh_sets("exact-finish"), exact_finish, "MAX_OBJECTS", VARIANTS, METRICS, PLACERS)
    store(HERE, runs, variant_report("the exact finish", "fresh plans", runs, tuple(VARIANTS), PLACERS))
