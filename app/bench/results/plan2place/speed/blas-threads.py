"""DFS and Plan2Place with numpy's BLAS threads and with one (models.placement.blas), alone and beside a neighbour.

In one process DFS and Plan2Place take turns plan by plan, both in one variant, the variant alternating from run to
run (the limit switched off by patching `blas.one_blas_thread`). "beside a neighbour": a second process solves the
same set's plans with Plan2Place and DFS all along, in the same variant as the measured run, as the placement bench's
second worker does. Prints the p50 per object and its ratio to DFS's per condition and variant, and how many
layouts the two variants share. Run from a tree's root:

    PYTHONPATH=. python app/bench/results/plan2place/speed/blas-threads.py unseen_a dense [--n 20] [--seeds 2]
"""
import argparse
import contextlib
import multiprocessing as mp
import time

import numpy as np

from app.bench.paired import fingerprint
from app.bench.plan2place import pick_records
from models.placement import blas
from models.placement.base import get_solver

VARIANTS = {"numpy's threads": contextlib.nullcontext, "one thread": blas.one_blas_thread}
NAMES = list(VARIANTS)


def solve(solver, plan, seed: int, variant: str):
    blas.one_blas_thread = VARIANTS[variant]
    return solver.solve(plan, seed=seed)


def neighbour(dataset: str, n: int, variant, stop) -> None:
    """Solve the set's plans with Plan2Place and DFS until `stop`, each solve in the variant `variant` names."""
    plans = [r.plan for r in pick_records(dataset, n)][::-1]
    p2p, dfs = get_solver("plan2place"), get_solver("dfs")
    while not stop.is_set():
        for plan in plans:
            if stop.is_set():
                return
            solve(p2p, plan, 0, NAMES[variant.value])
            solve(dfs, plan, 0, NAMES[variant.value])


def measure(dataset: str, n: int, seeds: int, variant=None) -> dict:
    """ms per object of DFS and of Plan2Place in each variant, and each Plan2Place layout's fingerprint."""
    plans = [r.plan for r in pick_records(dataset, n)]
    p2p, dfs = get_solver("plan2place"), get_solver("dfs")
    for name in NAMES:
        solve(p2p, plans[0], 0, name)
        solve(dfs, plans[0], 0, name)
    out = {name: {"dfs": [], "plan2place": [], "layouts": []} for name in NAMES}
    k = 0
    for seed in range(seeds):
        for plan in plans:
            k += 1
            for name in NAMES[::1 if k % 2 else -1]:
                if variant is not None:
                    variant.value = NAMES.index(name)
                    time.sleep(0.05)  # the neighbour's solve under way ends in the variant before
                per = max(len(plan.objects), 1)
                t = time.perf_counter()
                solve(dfs, plan, seed, name)
                out[name]["dfs"].append(1000 * (time.perf_counter() - t) / per)
                t = time.perf_counter()
                layout = solve(p2p, plan, seed, name)
                out[name]["plan2place"].append(1000 * (time.perf_counter() - t) / per)
                out[name]["layouts"].append(fingerprint(layout))
    return out


def report(dataset: str, condition: str, out: dict) -> list[str]:
    lines = []
    for name in NAMES:
        dfs, p2p = np.median(out[name]["dfs"]), np.median(out[name]["plan2place"])
        lines.append(f"| {dataset} | {condition} | {name} | {dfs:.1f} | {p2p:.1f} | {p2p / dfs:.2f} |")
    same = sum(a == b for a, b in zip(*(out[name]["layouts"] for name in NAMES)))
    lines.append(f"| {dataset} | {condition} | layouts the same | {same} of {len(out[NAMES[0]]['layouts'])} | | |")
    return lines


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("datasets", nargs="+")
    ap.add_argument("--n", type=int, default=20)
    ap.add_argument("--seeds", type=int, default=2)
    a = ap.parse_args()
    print(f"p50 ms per object, {a.n} plans x {a.seeds} seeds per set; the variant alternating run by run\n")
    print("| set | condition | BLAS | DFS p50 | Plan2Place p50 | x DFS |\n| --- | --- | --- | --- | --- | --- |")
    ctx = mp.get_context("spawn")  # no fork of a process whose BLAS threads already run
    for dataset in a.datasets:
        for line in report(dataset, "alone", measure(dataset, a.n, a.seeds)):
            print(line, flush=True)
        variant, stop = ctx.Value("i", 0), ctx.Event()
        other = ctx.Process(target=neighbour, args=(dataset, a.n, variant, stop))
        other.start()
        try:
            time.sleep(5)  # its imports and warm-up
            for line in report(dataset, "beside a neighbour", measure(dataset, a.n, a.seeds, variant)):
                print(line, flush=True)
        finally:
            stop.set()
            other.join(timeout=60)
            if other.is_alive():
                other.terminate()


if __name__ == "__main__":
    main()
