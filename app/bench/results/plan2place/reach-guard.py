"""The reach guard (Episode.guarded) on and off, for greedy and Plan2Place, on plans no benchmark table uses: per
set, 16 plans halfway between the placement bench's 20 evenly spaced ones, seeds 0 and 1. Run from the
repository root:

    python app/bench/results/plan2place/reach-guard.py > app/bench/results/plan2place/reach-guard.md
"""

import statistics
import time

from app.bench.placement import score
from models.datasets import load_dataset
from models.placement.greedy import GreedySolver
from models.placement.plan2place.solver import Plan2PlaceSolver

SETS, PLANS, SEEDS = ("seen", "unseen_a", "unseen_b", "dense", "human"), 16, (0, 1)
METRICS = (("key_nav", 100, "Key_NAV"), ("cnt", 100, "CNT"), ("constraint_satisfaction", 100, "constraints"),
           ("realism", 100, "realism"), ("energy", 1, "energy"), ("nav", 100, "NAV"))


def off_sample(dataset: str) -> list:
    records = load_dataset(dataset, "validation" if dataset == "seen" else None)
    step = max(len(records) // 20, 1)  # the bench takes records[::step][:20]
    return [r for i, r in enumerate(records) if i % step == step // 2][:PLANS]


def mean(rows: list[dict], key: str, scale: float) -> str:
    values = [r[key] for r in rows if r[key] is not None]
    return f"{scale * statistics.mean(values):.2f}"


def main() -> None:
    print("| set | solver | guard | " + " | ".join(label for *_, label in METRICS) + " | ms per object (p50) |")
    print("| --- | --- | --- | " + " | ".join("---" for _ in METRICS) + " | --- |")
    for dataset in SETS:
        records = off_sample(dataset)
        for name, make in (("greedy", GreedySolver), ("plan2place", Plan2PlaceSolver)):
            for guard in (False, True):
                solver, rows, per_object = make(guard=guard), [], []
                for r in records:
                    for seed in SEEDS:
                        t0 = time.process_time()
                        layout = solver.solve(r.plan, seed=seed)
                        per_object.append(1000 * (time.process_time() - t0) / len(r.plan.objects))
                        rows.append(score(r.plan, layout))
                cells = " | ".join(mean(rows, key, scale) for key, scale, _ in METRICS)
                print(f"| {dataset} | {name} | {'on' if guard else 'off'} | {cells} | {statistics.median(per_object):.1f} |")


if __name__ == "__main__":
    main()
