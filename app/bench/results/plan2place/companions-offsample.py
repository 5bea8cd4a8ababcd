"""The companions' pass on and off, on plans no benchmark table uses: per set, 16 plans off the placement
bench's evenly spaced sample (the ones halfway between), seed 0, greedy and the shipped Plan2Place.
Switching the pass off replaces `models.placement.repair.keep_companions` for the run (a measurement
script, not a solver option). Run from the repository root:

    python app/bench/results/plan2place/companions-offsample.py > app/bench/results/plan2place/companions-offsample.md
"""

import statistics
import time

import models.placement.repair as repair
from app.bench.placement import score
from models.datasets import load_dataset
from models.placement import get_solver

SETS, SOLVERS, PLANS = ("seen", "unseen_a", "unseen_b", "dense", "human"), ("greedy", "plan2place"), 16


def off_sample(dataset: str) -> list:
    records = load_dataset(dataset, "validation" if dataset == "seen" else None)
    step = max(len(records) // 8, 1)  # the bench picks records[::step]
    return [r for i, r in enumerate(records) if i % step == step // 2][:PLANS]


def main() -> None:
    kept = repair.keep_companions
    print("| set | solver | companions' pass | realism | constraints | Key_NAV | energy | ms per object (p50) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for dataset in SETS:
        records = off_sample(dataset)
        for name in SOLVERS:
            solver = get_solver(name)
            for on in (False, True):
                repair.keep_companions = kept if on else (lambda ep, observer=None: [])
                rows, per_object = [], []
                for r in records:
                    t0 = time.perf_counter()
                    layout = solver.solve(r.plan, seed=0)
                    per_object.append(1000 * (time.perf_counter() - t0) / len(r.plan.objects))
                    rows.append(score(r.plan, layout))

                def mean(key, scale=100.0):
                    values = [x[key] for x in rows if x[key] is not None]
                    return scale * statistics.mean(values)
                print(f"| {dataset} | {name} | {'on' if on else 'off'} | {mean('realism'):.1f} | "
                      f"{mean('constraint_satisfaction'):.1f} | {mean('key_nav'):.1f} | {mean('energy', 1.0):.3f} | "
                      f"{statistics.median(per_object):.1f} |", flush=True)
    repair.keep_companions = kept


if __name__ == "__main__":
    main()
