"""Plan2Place against DFS (the default solver before), paired on the placement bench's stored runs: for each
set and metric, the mean difference plan2place - dfs over the same (plan, seed) pairs and a 95 % bootstrap
interval over plans (plans resampled, their seeds kept together). Reads app/bench/results/placement-*/results.json,
writes default-choice.md beside this script: python app/bench/results/plan2place/default-choice.py"""

from pathlib import Path

from app.bench.paired import stored_table

RESULTS = Path(__file__).resolve().parents[1]
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
# metric, scale, whether higher is better
METRICS = (("cnt", 100, True, 2), ("key_nav", 100, True, 2), ("nav", 100, True, 2),
           ("constraint_satisfaction", 100, True, 2), ("realism", 100, True, 2), ("energy", 1, False, 2),
           ("pto", 1000, False, 2))


def main() -> str:
    return stored_table(RESULTS, SETS, METRICS, lambda *_: "dfs",
                        "Plan2Place - DFS, mean over the same (plan, seed) pairs, [95 % bootstrap interval over plans]; "
                        "metrics x 100, energy as is, PTO in ms per object; **bold** = Plan2Place better with the "
                        "interval clear of 0, _italic_ = worse with the interval clear of 0.")


if __name__ == "__main__":
    text = main()
    (Path(__file__).parent / "default-choice.md").write_text(text)
    print(text)
