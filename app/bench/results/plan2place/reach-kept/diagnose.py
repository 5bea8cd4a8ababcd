"""Solving again with every task object kept reachable (models.placement.reach_kept) against not (`ROUNDS` 0), on the
diagnosis plans (20 per set x 2 seeds; never the bench's or fresh plans), Plan2Place and greedy alternating in one
process; writes `diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/reach-kept/diagnose.py
"""
import json
import sys
from pathlib import Path

from app.bench.paired import alternating, header, variant_rows
from models.placement import reach_kept

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "broken-first"))
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from diagnose import METRICS, SETS, p50s  # noqa: E402  (broken-first's)
from run import diagnosis_plans  # noqa: E402

VARIANTS = ("without", "reach-kept")
PLACERS = ("plan2place", "greedy")

if __name__ == "__main__":
    plan_sets = {ds: (diagnosis_plans(ds, 20), range(2)) for ds in sys.argv[1:] or SETS}
    rows = alternating(plan_sets, reach_kept, "ROUNDS", dict(zip(VARIANTS, (0, reach_kept.ROUNDS))), METRICS, PLACERS)
    (HERE / "diagnose.json").write_text(json.dumps(rows))
    report = "\n".join(["reach-kept - without, diagnosis plans, mean over the same (plan, seed) runs [95 % bootstrap "
                        "interval over plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating "
                        "in one process); **bold** = better with the interval clear of 0, _italic_ = worse.", "",
                        *header("set / placer", METRICS), *variant_rows(rows, *VARIANTS, METRICS, PLACERS), "",
                        "PTO p50 per object (ms), without -> with:", "", *p50s(rows, PLACERS, VARIANTS)]) + "\n"
    (HERE / "diagnose.md").write_text(report)
    print(report)
