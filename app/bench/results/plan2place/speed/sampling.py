"""Where Plan2Place's time goes: a py-spy sampling profile of 20 bench plans x 5 seeds of a set, folded to the share
of the samples inside each function (inclusive), the warm-up solve left out.

    pip install py-spy   # not a project dependency
    py-spy record -r 500 -f raw -o /tmp/p.raw -- python app/bench/results/plan2place/speed/sampling.py run unseen_a
    python app/bench/results/plan2place/speed/sampling.py fold /tmp/p.raw
"""
import collections
import re
import sys


def run(dataset: str) -> None:
    import torch

    from app.bench.placement import pick_records
    from models.placement import get_solver
    torch.set_num_threads(1)
    plans = [r.plan for r in pick_records(dataset, 20)]
    solver = get_solver("plan2place")
    solver.solve(plans[0], seed=0)  # warm-up: not in `timed`
    timed(solver, plans)


def timed(solver, plans) -> None:
    for seed in range(5):
        for plan in plans:
            solver.solve(plan, seed=seed)


def fold(path: str, top: int = 30) -> None:
    inside, total = collections.Counter(), 0
    for line in open(path):
        stack, n = line.rstrip().rsplit(" ", 1)
        frames = stack.split(";")
        if not any(f.startswith("timed ") for f in frames):
            continue
        total += int(n)
        for name in {re.sub(r" \(.*", "", f) for f in frames}:
            inside[name] += int(n)
    print(f"{total} samples in the timed solves; share of them inside each function:")
    for name, n in inside.most_common(top):
        print(f"{100 * n / total:5.1f} %  {name}")


if __name__ == "__main__":
    run(sys.argv[2]) if sys.argv[1] == "run" else fold(sys.argv[2])
