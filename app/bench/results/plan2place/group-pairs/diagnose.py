"""Group moves whose first object leaves its partners room (variant.py) against the shipped ones on the diagnosis
plans (20 per set x 2 seeds; never the bench's or fresh plans), Plan2Place and greedy (they share the repairs), the
variants alternating in one process. `paired`: every group move narrowed, every pose judged (-> `diagnose.md`,
`.json`); `fallback`: the shipped move, and the narrowed one only where it finds none, 8 poses judged (->
`diagnose-fallback.md`, `.json`):

    PYTHONPATH=. python app/bench/results/plan2place/group-pairs/diagnose.py paired|fallback [SET ...]
"""
import json
import sys
from pathlib import Path

import variant
from app.bench.gates import SETS, METRICS, diagnosis_plans, variant_report
from app.bench.paired import alternating
from models.placement import groups

PLACERS = ("plan2place", "greedy")
KINDS = {  # kind -> (its attribute of models.placement.groups, the variant, judged poses, the files' stem)
    "paired": ("_orders", variant.orders_paired, 0, "diagnose"),
    "fallback": ("group_move", variant.move_fallback, 8, "diagnose-fallback"),
}

if __name__ == "__main__":
    here, kind, sets = Path(__file__).parent, sys.argv[1], sys.argv[2:] or SETS
    attribute, changed, variant.SPREAD, stem = KINDS[kind]
    plan_sets = {ds: (diagnosis_plans(ds, 20), range(2)) for ds in sets}
    rows = alternating(plan_sets, groups, attribute, {"shipped": getattr(groups, attribute), kind: changed}, METRICS,
                       PLACERS)
    (here / f"{stem}.json").write_text(json.dumps(rows))
    (here / f"{stem}.md").write_text(report := variant_report(kind, "diagnosis plans", rows, ("shipped", kind), PLACERS))
    print(report)
