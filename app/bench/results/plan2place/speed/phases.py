"""Where the median Plan2Place run of a bench set spends its time: each run (the set's bench plans x seed 0, one
process, torch threads 1) timed whole and in its phases, per object: the repairs (models.placement.repair), the
second solve with the objects of broken constraints first including the repairs it runs (reorder.broken_first),
the reach-kept solve, the restarts and the exact finish; then the network path (observe, choose_subset and the
actor's forward pass) per step. Printed: the p50, and the p50 each phase's removal would leave (a bound: the
runs are not re-solved).

    python app/bench/results/plan2place/speed/phases.py human 120 > app/bench/results/plan2place/speed/phases-human.txt
"""
import collections
import sys
import time

import numpy as np
import torch

import models.placement.exact_finish as exact_finish
import models.placement.plan2place.policy as policy
import models.placement.reach_kept as reach_kept
import models.placement.reorder as reorder
import models.placement.repair as repair
import models.placement.restarts as restarts
from app.bench.placement import pick_records
from models.placement import get_solver

spent, calls = collections.Counter(), collections.Counter()


def timed(owner, name: str, phase: str) -> None:
    inner = getattr(owner, name)

    def call(*args, **kwargs):
        start = time.perf_counter()
        try:
            return inner(*args, **kwargs)
        finally:
            spent[phase] += time.perf_counter() - start
            calls[phase] += 1
    setattr(owner, name, call)


PHASES = {"repairs": (repair, "repair"), "second solve": (reorder, "broken_first"),
          "reach-kept": (reach_kept, "solve_keeping"), "restarts": (restarts, "restarted"),
          "exact finish": (exact_finish, "finished_exactly"), "observe": (policy, "observe"),
          "subset": (policy, "choose_subset"), "forward": (policy.NumpyPolicy, "__call__")}
NETWORK = ("observe", "subset", "forward")


def main(dataset: str, n: int) -> None:
    torch.set_num_threads(1)
    for phase, (owner, name) in PHASES.items():
        timed(owner, name, phase)
    plans = [r.plan for r in pick_records(dataset, n)]
    solver = get_solver("plan2place")
    solver.solve(plans[0], seed=0)  # warm-up
    runs, per_call, total_calls = [], collections.Counter(), collections.Counter()
    for plan in plans:
        spent.clear(), calls.clear()
        start = time.perf_counter()
        solver.solve(plan, seed=0)
        ms = 1000 / len(plan.objects)
        runs.append(((time.perf_counter() - start) * ms, {p: spent[p] * ms for p in PHASES}))
        per_call.update(spent), total_calls.update(calls)
    whole = np.array([r[0] for r in runs])
    print(f"{dataset}: {len(runs)} runs (seed 0), Plan2Place alone in one process; ms per object")
    print(f"p50 {np.median(whole):.2f}, p90 {np.percentile(whole, 90):.2f}")
    print("| phase | runs where it took > 0.5 ms per object | p50 without it |\n| --- | --- | --- |")
    for phase in (*(p for p in PHASES if p not in NETWORK), "network path"):
        cost = np.array([sum(r[1][p] for p in NETWORK) if phase == "network path" else r[1][phase] for r in runs])
        print(f"| {phase} | {int((cost > 0.5).sum())} | {np.median(whole - cost):.2f} |")
    steps = total_calls["forward"]
    print(f"network path per step ({steps} steps, {steps / sum(len(p.objects) for p in plans):.2f} per object): "
          + ", ".join(f"{p} {per_call[p] / steps * 1e6:.0f} us" for p in NETWORK))
    print("(the second solve's time includes the repairs it runs; the restarts' includes every phase they run again)")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
