"""decision.md's gate: Plan2Place and greedy with the shipped reach-kept solve and with `variant.walls_first` on fresh
plans (tag `walls-first`: 48 `dense` x 5 seeds, 24 per other set x 2 seeds; `human`: the earlier gates' 24 rooms x 2
seeds), alternating in one process; writes `runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/walls-first/gate.py
"""
from pathlib import Path

from app.bench.gates import METRICS, fresh_sets, variant_report
from app.bench.paired import alternating, store
from models.placement import reach_kept
from variant import walls_first

HERE = Path(__file__).parent
VARIANTS = ("shipped", "walls-first")
PLACERS = ("plan2place", "greedy")

if __name__ == "__main__":
    runs = alternating(fresh_sets("walls-first"), reach_kept, "solve_keeping",
                       dict(zip(VARIANTS, (reach_kept.solve_keeping, walls_first))), METRICS, PLACERS)
    store(HERE, runs, variant_report("walls-first", "fresh plans", runs, VARIANTS, PLACERS))
