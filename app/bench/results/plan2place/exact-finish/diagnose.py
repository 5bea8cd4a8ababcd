"""The exact finish (models.placement.exact_finish) off, and on for rooms of at most 9 or 17 objects to move, on the
diagnosis plans (20 per set x 2 seeds), Plan2Place and greedy alternating in one process; writes `diagnose.md` and
`diagnose.json` here. It ran on commit 0ae1f45's code without its `crowded` rule (added after this run), where
every step-wise placer finished this way; since then only `plan2place_exact` does (check that commit out to run it
again):

    PYTHONPATH=. python app/bench/results/plan2place/exact-finish/diagnose.py [SET ...]
"""
import json
import sys
from pathlib import Path

from app.bench.gates import METRICS, SETS, diagnosis_plans, variant_report
from app.bench.paired import alternating
from models.placement import exact_finish

HERE = Path(__file__).parent
VARIANTS = {"off": 0, "9": 9, "17": 17}
PLACERS = ("plan2place", "greedy")

if __name__ == "__main__":
    sets = tuple(sys.argv[1:]) or SETS
    rows = alternating({ds: (diagnosis_plans(ds, 20), range(2)) for ds in sets}, exact_finish, "MAX_OBJECTS",
                       VARIANTS, METRICS, PLACERS)
    (HERE / "diagnose.json").write_text(json.dumps(rows))
    report = "\n\n".join(variant_report(f"the exact finish up to {v} objects", "diagnosis plans", rows, ("off", v),
                                        PLACERS) for v in list(VARIANTS)[1:])
    (HERE / "diagnose.md").write_text(report)
    print(report)
