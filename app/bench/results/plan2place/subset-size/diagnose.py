"""How many of the lowest-energy candidates the policy chooses among (`features.TOP_K`, 40 in training and shipped;
plus `RANDOM_K` drawn from the rest): 40 against 80 and 20 on the diagnosis plans (20 per set x 2 seeds; never the
bench's or fresh plans), Plan2Place alone, the variants alternating in one process. At most steps several candidates
tie for the lowest energy and the policy's pick among them is what training changed (README, The learning proof):
with more of them in view it chooses among more. -> `diagnose.md`, `diagnose.json`:

    PYTHONPATH=. python app/bench/results/plan2place/subset-size/diagnose.py
"""
import json
from pathlib import Path

from app.bench.gates import SETS, METRICS, diagnosis_plans, variant_report
from app.bench.paired import alternating
from models.placement.plan2place import features

VARIANTS = {"top 40": 40, "top 80": 80, "top 20": 20}

if __name__ == "__main__":
    here = Path(__file__).parent
    plan_sets = {ds: (diagnosis_plans(ds, 20), range(2)) for ds in SETS}
    rows = alternating(plan_sets, features, "TOP_K", VARIANTS, METRICS, ("plan2place",))
    (here / "diagnose.json").write_text(json.dumps(rows))
    report = "\n\n".join(variant_report(v, "diagnosis plans", rows, ("top 40", v), ("plan2place",))
                         for v in list(VARIANTS)[1:])
    (here / "diagnose.md").write_text(report)
    print(report)
