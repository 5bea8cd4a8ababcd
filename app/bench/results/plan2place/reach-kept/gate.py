"""decision.md's gate: Plan2Place and greedy with and without solving again with every task object kept reachable
(models.placement.reach_kept; without: `ROUNDS` 0) on fresh plans (tag `reach-kept`: 48 `dense` x 5 seeds, 24 per
other set x 2 seeds; `human`: the group-moves gate's 24 rooms x 2 seeds), alternating in one process; writes
`runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/reach-kept/gate.py
"""
import importlib.util
import sys
from pathlib import Path

from app.bench.paired import alternating, header, store, variant_rows
from models.datasets.fresh import fresh_plans
from models.placement import reach_kept

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "broken-first"))
from diagnose import METRICS, SETS, p50s  # noqa: E402  (broken-first's)

_spec = importlib.util.spec_from_file_location("group_moves_gate", HERE.parent / "group-moves" / "gate.py")
group_moves_gate = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(group_moves_gate)

TAG = "reach-kept"
VARIANTS = ("without", "reach-kept")
PLACERS = ("plan2place", "greedy")


def run() -> list[dict]:
    plan_sets = {ds: (fresh_plans(ds, TAG, 48), range(5)) if ds == "dense" else
                 (group_moves_gate.human_plans() if ds == "human" else fresh_plans(ds, TAG, 24), range(2))
                 for ds in SETS}
    return alternating(plan_sets, reach_kept, "ROUNDS", dict(zip(VARIANTS, (0, reach_kept.ROUNDS))), METRICS, PLACERS)


def report(rows: list[dict]) -> str:
    return "\n".join(["reach-kept - without, fresh plans, mean over the same (plan, seed) runs [95 % bootstrap interval "
                      "over plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating in one "
                      "process); **bold** = better with the interval clear of 0, _italic_ = worse.", "",
                      *header("set / placer", METRICS), *variant_rows(rows, *VARIANTS, METRICS, PLACERS), "",
                      "PTO p50 per object (ms), without -> with:", "", *p50s(rows, PLACERS, VARIANTS)]) + "\n"


if __name__ == "__main__":
    runs = run()
    store(HERE, runs, report(runs))
