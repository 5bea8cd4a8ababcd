"""A coarser candidate grid (variant.py) against the shipped one on the diagnosis plans (20 per set x 2 seeds;
never the bench's or fresh plans), Plan2Place alone, the variants alternating in one process. `grid`: the whole grid
0.15 m and 0.2 m apart (-> `diagnose.md`, `.json`); `steps`: only the steps' candidates, the repairs on the shipped
grid (-> `diagnose-steps.md`, `.json`):

    PYTHONPATH=. python app/bench/results/plan2place/grid-step/diagnose.py grid|steps [SET ...]
"""
import json
import sys
from pathlib import Path

from app.bench.gates import METRICS, SETS, diagnosis_plans, variant_report
from app.bench.paired import alternating
from models.placement import greedy
from models.placement.candidates import CandidateScorer
from variant import SHIPPED, coarse_steps, spaced

KINDS = {  # kind -> (what is patched, its attribute, variants, the files' stem, a variant's label)
    "grid": (CandidateScorer, "__init__", {"shipped": SHIPPED, "0.15 m": spaced(0.15), "0.2 m": spaced(0.2)},
             "diagnose", "grid {}"),
    "steps": (greedy, "_steps", {"shipped": greedy._steps, "steps 0.15 m": coarse_steps(0.15),
                                 "steps 0.2 m": coarse_steps(0.2)}, "diagnose-steps", "{}"),
}

if __name__ == "__main__":
    here, kind, sets = Path(__file__).parent, sys.argv[1], sys.argv[2:] or SETS
    where, attribute, variants, stem, label = KINDS[kind]
    plan_sets = {ds: (diagnosis_plans(ds, 20), range(2)) for ds in sets}
    rows = alternating(plan_sets, where, attribute, variants, METRICS, ("plan2place",))
    (here / f"{stem}.json").write_text(json.dumps(rows))
    report = "\n\n".join(variant_report(label.format(v), "diagnosis plans", rows, ("shipped", v), ("plan2place",))
                         for v in list(variants)[1:])
    (here / f"{stem}.md").write_text(report)
    print(report)
