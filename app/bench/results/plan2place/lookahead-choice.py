"""The look-ahead placer against Plan2Place (the default), paired on the placement bench's stored runs: for each set
and metric, lookahead - plan2place over the same (plan, seed) pairs with a 95 % bootstrap interval over plans. Reads
app/bench/results/placement-*/results.json, writes lookahead-choice.md beside this script:
python app/bench/results/plan2place/lookahead-choice.py"""

from pathlib import Path

from app.bench.paired import stored_table

RESULTS = Path(__file__).resolve().parents[1]
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
METRICS = (("cnt", 100, True, 2), ("key_nav", 100, True, 2), ("constraint_satisfaction", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3), ("pto", 1000, False, 1))


def main() -> str:
    return stored_table(RESULTS, SETS, METRICS, lambda *_: "plan2place",
                        "Look-ahead - Plan2Place, mean over the same (plan, seed) pairs, [95 % bootstrap interval over "
                        "plans]; metrics x 100, energy as is, PTO in ms per object; **bold** = the look-ahead better with "
                        "the interval clear of 0, _italic_ = worse with the interval clear of 0.", a="lookahead")


if __name__ == "__main__":
    text = main()
    (Path(__file__).parent / "lookahead-choice.md").write_text(text)
    print(text)
