"""The realism judge's corner fix, measured on every solver alike: the same layouts scored by the judge as it
was (a wall-standing object had to face away from the *nearest* wall, which in a corner is picked by float
noise between two walls at distance 0) and as it is (away from a wall it touches, either one in a corner).
16 plans per set halfway between the placement bench's 20 evenly spaced ones, seed 0, the `human` set's own
arrangement as a row. Run from the repository root with the old judge's file extracted beside it:

    git show dd4cd4f:models/metrics/realism.py > /tmp/realism_old.py
    python app/bench/results/realism-corner/judge.py /tmp/realism_old.py > app/bench/results/realism-corner/judge.md
"""

import importlib.util
import statistics
import sys

from models.datasets import load_dataset
from models.metrics.realism import realism
from models.placement import get_solver

SETS, SOLVERS, PLANS = ("seen", "unseen_a", "unseen_b", "dense", "human"), ("dfs", "milp", "z3", "greedy", "plan2place"), 16


def off_sample(dataset: str) -> list:
    records = load_dataset(dataset, "validation" if dataset == "seen" else None)
    step = max(len(records) // 20, 1)  # the bench takes records[::step][:20]
    return [r for i, r in enumerate(records) if i % step == step // 2][:PLANS]


def main(old_path: str) -> None:
    spec = importlib.util.spec_from_file_location("realism_old", old_path)
    old = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(old)
    print("| set | solver | realism, old judge | realism, corner fix | layouts whose score changed |")
    print("| --- | --- | --- | --- | --- |")
    for dataset in SETS:
        records = off_sample(dataset)
        layouts: dict[str, list] = {name: [(r.plan, get_solver(name).solve(r.plan, seed=0)) for r in records]
                                    for name in SOLVERS}
        if dataset == "human":
            layouts["human"] = [(r.plan, r.reference) for r in records]
        for name, runs in layouts.items():
            before = [old.realism(p, lay) for p, lay in runs]
            after = [realism(p, lay) for p, lay in runs]
            pairs = [(b, a) for b, a in zip(before, after) if b is not None]
            print(f"| {dataset} | {name} | {100 * statistics.mean(b for b, _ in pairs):.2f} | "
                  f"{100 * statistics.mean(a for _, a in pairs):.2f} | {sum(b != a for b, a in pairs)} of {len(pairs)} |")


if __name__ == "__main__":
    main(sys.argv[1])
