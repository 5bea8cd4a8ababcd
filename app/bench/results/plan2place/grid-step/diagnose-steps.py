"""Coarser candidates for the steps only, the repairs on the shipped grid (variant.coarse_steps), against the
shipped placer on the diagnosis plans (20 per set x 2 seeds), Plan2Place alone, alternating in one process; writes
`diagnose-steps.md` and `diagnose-steps.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/grid-step/diagnose-steps.py [SET ...]
"""
import json
import sys
from pathlib import Path

from app.bench.gates import METRICS, SETS, diagnosis_plans, variant_report
from app.bench.paired import alternating
from models.placement import greedy
from variant import coarse_steps

if __name__ == "__main__":
    here, sets = Path(__file__).parent, sys.argv[1:] or SETS
    variants = {"shipped": greedy._steps, "steps 0.15 m": coarse_steps(0.15), "steps 0.2 m": coarse_steps(0.2)}
    plan_sets = {ds: (diagnosis_plans(ds, 20), range(2)) for ds in sets}
    rows = alternating(plan_sets, greedy, "_steps", variants, METRICS, ("plan2place",))
    (here / "diagnose-steps.json").write_text(json.dumps(rows))
    report = "\n\n".join(variant_report(f"{v}", "diagnosis plans", rows, ("shipped", v), ("plan2place",))
                         for v in list(variants)[1:])
    (here / "diagnose-steps.md").write_text(report)
    print(report)
