"""decision.md's gate: Plan2Place and greedy with and without solving again with every task object kept reachable
(models.placement.reach_kept; without: `ROUNDS` 0) on fresh plans (tag `reach-kept`: 48 `dense` x 5 seeds, 24 per
other set x 2 seeds; `human`: the group-moves gate's 24 rooms x 2 seeds), alternating in one process; writes
`runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/reach-kept/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, variant_report
from app.bench.paired import alternating, store
from models.placement import reach_kept

HERE = Path(__file__).parent
VARIANTS = ("without", "reach-kept")
PLACERS = ("plan2place", "greedy")

if __name__ == "__main__":
    runs = alternating(fresh_sets("reach-kept"), reach_kept, "ROUNDS", dict(zip(VARIANTS, (0, reach_kept.ROUNDS))),
                       METRICS, PLACERS)
    store(HERE, runs, variant_report("reach-kept", "fresh plans", runs, VARIANTS, PLACERS))
