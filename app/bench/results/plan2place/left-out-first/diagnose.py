"""Solving again with the left-out objects first (models.placement.again), against not (`ROUNDS` 0), on the diagnosis
plans (16 per set x 2 seeds, 20 on `dense`; never the bench's or fresh plans), alternating in one process; writes
`diagnose.md` and `diagnose.json` here. Run from the root of a tree of commit e019e2f (models.placement.again left
`models/` after the gate):

    PYTHONPATH=. python app/bench/results/plan2place/left-out-first/diagnose.py
"""
import json
import sys
from pathlib import Path

from app.bench.paired import alternating, header, variant_rows
from models.placement import again

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

SETS = {"dense": 20, "seen": 16, "unseen_a": 16, "unseen_b": 16, "human": 16}
METRICS = (("cnt", 100, True, 2), ("key_nav", 100, True, 2), ("constraint_satisfaction", 100, True, 2),
           ("energy", 1, False, 3), ("realism", 100, True, 2), ("pto_ms", 1, False, 2))

if __name__ == "__main__":
    plan_sets = {ds: (diagnosis_plans(ds, n), range(2)) for ds, n in SETS.items()}
    rows = alternating(plan_sets, again, "ROUNDS", {"without": 0, "left out first": again.ROUNDS}, METRICS)
    (HERE / "diagnose.json").write_text(json.dumps(rows))
    report = "\n".join(["left out first - without, diagnosis plans, mean over the same (plan, seed) runs [95 % "
                        "bootstrap interval over plans]; metrics x 100, energy as is, PTO in ms per object (the two "
                        "alternating in one process); **bold** = better with the interval clear of 0, _italic_ = worse.",
                        "", *header("set / placer", METRICS),
                        *variant_rows(rows, "without", "left out first", METRICS)]) + "\n"
    (HERE / "diagnose.md").write_text(report)
    print(report)
