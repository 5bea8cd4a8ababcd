"""Solving again with the objects of broken constraints first (models.placement.reorder) against not (`ROUNDS` 0), on
the diagnosis plans (16 per set x 2 seeds; never the bench's or fresh plans), alternating in one process; writes
`diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/broken-first/diagnose.py
"""
import json
import sys
from pathlib import Path

from app.bench.gates import METRICS, SETS, p50s
from app.bench.paired import alternating, header, variant_rows
from models.placement import reorder

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

VARIANTS = ("without", "broken first")
__all__ = ["METRICS", "SETS", "VARIANTS", "p50s"]  # the later experiments' scripts took these from here


if __name__ == "__main__":
    placers = ("plan2place",)
    plan_sets = {ds: (diagnosis_plans(ds, 16), range(2)) for ds in SETS}
    rows = alternating(plan_sets, reorder, "ROUNDS", dict(zip(VARIANTS, (0, reorder.ROUNDS))), METRICS, placers)
    (HERE / "diagnose.json").write_text(json.dumps(rows))
    report = "\n".join(["broken first - without, diagnosis plans, mean over the same (plan, seed) runs [95 % bootstrap "
                        "interval over plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating "
                        "in one process); **bold** = better with the interval clear of 0, _italic_ = worse.", "",
                        *header("set / placer", METRICS), *variant_rows(rows, *VARIANTS, METRICS, placers), "",
                        "PTO p50 per object (ms), without -> with:", "", *p50s(rows, placers, VARIANTS)]) + "\n"
    (HERE / "diagnose.md").write_text(report)
    print(report)
