"""A coarser candidate grid (variant.py) against the shipped one on the diagnosis plans (20 per set x 2 seeds;
never the bench's or fresh plans), Plan2Place alone, the variants alternating in one process; writes
`diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/grid-step/diagnose.py [SET ...]
"""
import json
import sys
from pathlib import Path

from app.bench.gates import METRICS, SETS, diagnosis_plans, variant_report
from app.bench.paired import alternating
from models.placement.candidates import CandidateScorer
from variant import SHIPPED, spaced

if __name__ == "__main__":
    here, sets = Path(__file__).parent, sys.argv[1:] or SETS
    variants = {"shipped": SHIPPED, "0.15 m": spaced(0.15), "0.2 m": spaced(0.2)}
    plan_sets = {ds: (diagnosis_plans(ds, 20), range(2)) for ds in sets}
    rows = alternating(plan_sets, CandidateScorer, "__init__", variants, METRICS, ("plan2place",))
    (here / "diagnose.json").write_text(json.dumps(rows))
    report = "\n\n".join(variant_report(f"grid {v}", "diagnosis plans", rows, ("shipped", v), ("plan2place",))
                         for v in list(variants)[1:])
    (here / "diagnose.md").write_text(report)
    print(report)
