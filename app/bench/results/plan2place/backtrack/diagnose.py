"""Going back when an object finds no room (models.placement.backtrack) against not (`DEPTH` 0), on the diagnosis
plans (20 per set x 2 seeds; never the bench's or fresh plans), Plan2Place and greedy alternating in one process;
writes `diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/backtrack/diagnose.py
"""
import json
import sys
from pathlib import Path

from app.bench.paired import alternating, header, variant_rows
from models.placement import backtrack

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "broken-first"))
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from diagnose import METRICS, SETS, p50s  # noqa: E402  (broken-first's)
from run import diagnosis_plans  # noqa: E402

VARIANTS = ("without", "backtrack")
PLACERS = ("plan2place", "greedy")

if __name__ == "__main__":
    plan_sets = {ds: (diagnosis_plans(ds, 20), range(2)) for ds in sys.argv[1:] or SETS}
    variants = dict(zip(VARIANTS, (0, backtrack.DEPTH)))
    rows = alternating(plan_sets, backtrack, "DEPTH", variants, METRICS, PLACERS)
    (HERE / "diagnose.json").write_text(json.dumps(rows))
    report = "\n".join([f"backtrack (DEPTH {backtrack.DEPTH}, TRIES {backtrack.TRIES}) - without, diagnosis plans, "
                        "mean over the same (plan, seed) runs [95 % bootstrap interval over plans]; metrics x 100, "
                        "energy as is, PTO in ms per object (the two alternating in one process); **bold** = better "
                        "with the interval clear of 0, _italic_ = worse.", "",
                        *header("set / placer", METRICS), *variant_rows(rows, *VARIANTS, METRICS, PLACERS), "",
                        "PTO p50 per object (ms), without -> with:", "", *p50s(rows, PLACERS, VARIANTS)]) + "\n"
    (HERE / "diagnose.md").write_text(report)
    print(report)
