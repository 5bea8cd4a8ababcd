"""Solving again with the objects of broken constraints first (models.placement.reorder) against not (`ROUNDS` 0), on
the diagnosis plans (16 per set x 2 seeds; never the bench's or fresh plans), alternating in one process; writes
`diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/broken-first/diagnose.py
"""
import json
import statistics
import sys
from pathlib import Path

from app.bench.paired import alternating, header, variant_rows
from models.placement import reorder

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
METRICS = (("cnt", 100, True, 2), ("key_nav", 100, True, 2), ("constraint_satisfaction", 100, True, 2),
           ("energy", 1, False, 3), ("realism", 100, True, 2), ("pto_ms", 1, False, 2))
VARIANTS = ("without", "broken first")


def p50s(rows: list[dict], placers, variants=VARIANTS) -> list[str]:
    """The PTO p50 per object of each set and placer, the first variant -> the second."""
    out = []
    for label in dict.fromkeys(r["set"] for r in rows):
        for placer in placers:
            p50 = [statistics.median(r["pto_ms"] for r in rows if (r["set"], r["placer"], r["solver"]) ==
                                     (label, placer, v)) for v in variants]
            out.append(f"- {label} / {placer}: {p50[0]:.2f} -> {p50[1]:.2f} ({100 * (p50[1] / p50[0] - 1):+.1f} %)")
    return out


if __name__ == "__main__":
    placers = ("plan2place",)
    plan_sets = {ds: (diagnosis_plans(ds, 16), range(2)) for ds in SETS}
    rows = alternating(plan_sets, reorder, "ROUNDS", dict(zip(VARIANTS, (0, reorder.ROUNDS))), METRICS, placers)
    (HERE / "diagnose.json").write_text(json.dumps(rows))
    report = "\n".join(["broken first - without, diagnosis plans, mean over the same (plan, seed) runs [95 % bootstrap "
                        "interval over plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating "
                        "in one process); **bold** = better with the interval clear of 0, _italic_ = worse.", "",
                        *header("set / placer", METRICS), *variant_rows(rows, *VARIANTS, METRICS, placers), "",
                        "PTO p50 per object (ms), without -> with:", "", *p50s(rows, placers)]) + "\n"
    (HERE / "diagnose.md").write_text(report)
    print(report)
