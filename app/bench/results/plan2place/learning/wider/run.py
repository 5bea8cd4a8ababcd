"""The learning bench on more plans (decision.md): the six solvers of `h3ds bench plan2place` on plans of a set that
`../wide/` did not use, seeds 0-2 (`human`: its 120 rooms at seeds 3-7); one shard of them per process. Writes
<set>/results-<k>.json.gz.

    python app/bench/results/plan2place/learning/wider/run.py dense 0 2   # shard 0 of 2
"""
import gzip
import json
import sys
from pathlib import Path

from app.bench.placement import pick_records
from app.bench.plan2place import evaluate, proof_solvers, shipped_path
from models.datasets import load_dataset

HERE = Path(__file__).parent
OLD = {"seen": 120, "unseen_a": 100, "unseen_b": 100, "dense": 100, "human": 120}  # plans of ../wide per set
NEW, SEEDS, CHECKED = 300, 3, 4
HUMAN_SEEDS = range(3, 8)


def new_plans(dataset: str) -> list:
    """`NEW` plans evenly spaced among those the wide bench did not use (all of them if fewer)."""
    used = {r.plan.id for r in pick_records(dataset, OLD[dataset])}
    rest = [r.plan for r in load_dataset(dataset, "validation" if dataset == "seen" else None) if r.plan.id not in used]
    step = max(len(rest) // NEW, 1)
    return rest[::step][:NEW]


def solvers() -> list:
    """`h3ds bench plan2place`'s six solvers for the shipped weights."""
    return [s for group in proof_solvers([shipped_path()]) for s in group]


def check_old(dataset: str, every: list) -> list[str]:
    """The first `CHECKED` plans of the wide sample solved again at seed 0: the rows that differ from those stored."""
    stored = {(r["solver"], r["plan"], r["seed"]): r for r in
              json.loads((HERE.parent / "wide" / dataset / "results.json").read_text())}
    plans = [r.plan for r in pick_records(dataset, OLD[dataset])][:CHECKED]
    rows = [r for rs in evaluate(every, plans, 1).values() for r in rs]
    keys = ("energy", "constraint_satisfaction", "cnt", "key_nav")
    return [f"{r['solver']} {r['plan']}" for r in rows
            if any(r[k] != stored[(r["solver"], r["plan"], 0)][k] for k in keys)]


def main(dataset: str, shard: int, shards: int) -> None:
    every = solvers()
    out = HERE / dataset
    out.mkdir(exist_ok=True)
    if shard == 0:
        differ = check_old(dataset, every)
        (out / "check.txt").write_text(f"{CHECKED} plans of ../wide/{dataset} at seed 0 solved again: "
                                       f"{len(differ)} rows differ from the stored ones {differ}\n")
    if dataset == "human":  # no more rooms: the same 120 at seeds `HUMAN_SEEDS` (decision.md)
        plans = [r.plan for r in pick_records(dataset, OLD[dataset])][shard::shards]
    else:
        plans = new_plans(dataset)[shard::shards]
    seeds = HUMAN_SEEDS if dataset == "human" else range(SEEDS)
    rows = [r for rs in evaluate(every, plans, seeds).values() for r in rs]
    (out / f"results-{shard}.json.gz").write_bytes(gzip.compress(json.dumps(rows).encode()))
    print(dataset, shard, len(plans), "plans done")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
