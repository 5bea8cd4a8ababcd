"""Keeping the reach-kept solve (models.placement.reach_kept) whenever it leaves fewer task objects out of the robot's
reach, instead of only where its energy is also lower: the shipped rule against two variants, on the diagnosis plans
(20 per set x 2 seeds; never the bench's or fresh plans), Plan2Place and greedy alternating in one process; writes
`diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/reach-over-energy/diagnose.py [SET ...]
"""
import json
import sys
from pathlib import Path

from app.bench.gates import METRICS, SETS, diagnosis_plans, variant_report
from app.bench.paired import alternating
from models.placement import reach_kept

HERE = Path(__file__).parent
SHIPPED = reach_kept.better


def reach(new, old) -> bool:
    """Fewer task objects out of reach, whatever the energy."""
    return reach_kept.out_of_reach(new) < reach_kept.out_of_reach(old)


def reach_one_more(new, old) -> bool:
    """Fewer task objects out of reach, with at most one object more left out."""
    return reach(new, old) and len(new.failed) <= len(old.failed) + 1


VARIANTS = {"energy": SHIPPED, "reach": reach, "reach_one_more": reach_one_more}

if __name__ == "__main__":
    sets = sys.argv[1:] or SETS
    rows = alternating({ds: (diagnosis_plans(ds, 20), range(2)) for ds in sets}, reach_kept, "better", VARIANTS,
                       METRICS, ("plan2place", "greedy"))
    (HERE / "diagnose.json").write_text(json.dumps(rows))
    report = "\n\n".join(variant_report(v, "diagnosis plans", rows, ("energy", v), ("plan2place", "greedy"))
                         for v in list(VARIANTS)[1:])
    (HERE / "diagnose.md").write_text(report)
    print(report)
