"""Plan2Place against the best other solver of each metric, paired on the placement bench's stored runs: for each
set and target metric, the solver with the best mean besides Plan2Place, and plan2place - that solver over the
same (plan, seed) pairs with a 95 % bootstrap interval over plans (app.bench.paired). A lead or a gap whose
interval holds 0 is within the plans' noise. Reads app/bench/results/placement-*/results.json, writes targets.md
beside this script: python app/bench/results/plan2place/targets.py"""

from pathlib import Path

import numpy as np

from app.bench.paired import stored_table

RESULTS = Path(__file__).resolve().parents[1]
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
# the target metrics: metric, scale, whether higher is better, digits
METRICS = (("cnt", 100, True, 2), ("key_nav", 100, True, 2), ("constraint_satisfaction", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3))


# Not compared: the people's layouts of `human`, and the look-ahead placer, a slower option of this project that the
# issue's targets (against its baselines) do not name; it is compared in lookahead-choice.md.
NOT_COMPARED = {"plan2place", "human", "lookahead"}


def best_other(rows: list[dict], metric: str, up: bool) -> str:
    """The solver other than Plan2Place with the best mean of `metric` (`NOT_COMPARED` excepted)."""
    means = {}
    for s in sorted({r["solver"] for r in rows} - NOT_COMPARED):  # ties: the first by name
        vals = [r[metric] for r in rows if r["solver"] == s and r.get(metric) is not None]
        if vals:
            means[s] = float(np.mean(vals))
    return (max if up else min)(means, key=means.get)


def main() -> str:
    return stored_table(RESULTS, SETS, METRICS, best_other,
                        "Plan2Place - the best other solver of each metric (named), mean over the same (plan, seed) "
                        "pairs, [95 % bootstrap interval over plans]; metrics x 100, energy as is; **bold** = Plan2Place "
                        "better with the interval clear of 0, _italic_ = worse with the interval clear of 0, plain = "
                        "within the plans' noise.", name_other=True)


if __name__ == "__main__":
    text = main()
    (Path(__file__).parent / "targets.md").write_text(text)
    print(text)
