"""decision.md's gate: Plan2Place and greedy with and without solving again with every task object kept reachable
(models.placement.reach_kept; without: `switched_off` in place of `solve_keeping`, what `keep_reach=False` does;
the module's `ROUNDS` 0 when this ran) on fresh plans (tag `reach-kept`: 48 `dense` x 5 seeds, 24 per
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


def switched_off(ep, *_):
    """`solve_keeping` switched off: the repaired episode as it is."""
    return ep


if __name__ == "__main__":
    runs = alternating(fresh_sets("reach-kept"), reach_kept, "solve_keeping",
                       dict(zip(VARIANTS, (switched_off, reach_kept.solve_keeping))), METRICS, PLACERS)
    store(HERE, runs, variant_report("reach-kept", "fresh plans", runs, VARIANTS, PLACERS))
