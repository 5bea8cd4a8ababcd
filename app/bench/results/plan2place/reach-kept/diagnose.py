"""Solving again with every task object kept reachable (models.placement.reach_kept) against not (`ROUNDS` 0), on the
diagnosis plans (20 per set x 2 seeds; never the bench's or fresh plans), Plan2Place and greedy alternating in one
process; writes `diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/reach-kept/diagnose.py
"""
import json
import sys
from pathlib import Path

from app.bench.gates import METRICS, SETS, variant_report
from app.bench.paired import alternating
from models.placement import reach_kept

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

VARIANTS = ("without", "reach-kept")
PLACERS = ("plan2place", "greedy")

if __name__ == "__main__":
    plan_sets = {ds: (diagnosis_plans(ds, 20), range(2)) for ds in sys.argv[1:] or SETS}
    rows = alternating(plan_sets, reach_kept, "ROUNDS", dict(zip(VARIANTS, (0, reach_kept.ROUNDS))), METRICS, PLACERS)
    (HERE / "diagnose.json").write_text(json.dumps(rows))
    report = variant_report("reach-kept", "diagnosis plans", rows, VARIANTS, PLACERS)
    (HERE / "diagnose.md").write_text(report)
    print(report)
