"""The restarts' draws (models.placement.restarts.drawn) from the placer's probabilities flattened or sharpened by a
temperature T (each probability to the power 1 / T, normalised; T = 1: the shipped draw), on the diagnosis plans of
`dense` and `human` (the sets where an object is left out; 20 plans x 2 seeds), Plan2Place and greedy alternating in
one process; writes `diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/restart-temperature/diagnose.py [SET ...]
"""
import json
import sys
from pathlib import Path

import numpy as np

from app.bench.gates import METRICS, diagnosis_plans, variant_report
from app.bench.paired import alternating
from models.placement import restarts

HERE = Path(__file__).parent
SHIPPED = restarts.drawn
PLACERS = ("plan2place", "greedy")


def tempered(t: float):
    """`restarts.drawn` drawing from the probabilities to the power 1 / `t`."""
    def drawn(choose):
        def flattened(ep, opts, rng):
            pick, probs, why = choose(ep, opts, rng)
            p = np.asarray(probs, float) ** (1 / t)
            return pick, p / p.sum(), why
        return SHIPPED(flattened)
    return drawn


VARIANTS = {"T1": SHIPPED, "T3": tempered(3.0), "T0.3": tempered(0.3)}

if __name__ == "__main__":
    sets = sys.argv[1:] or ("dense", "human")
    rows = alternating({ds: (diagnosis_plans(ds, 20), range(2)) for ds in sets}, restarts, "drawn", VARIANTS, METRICS,
                       PLACERS)
    (HERE / "diagnose.json").write_text(json.dumps(rows))
    report = "\n\n".join(variant_report(v, "diagnosis plans", rows, ("T1", v), PLACERS) for v in list(VARIANTS)[1:])
    (HERE / "diagnose.md").write_text(report)
    print(report)
