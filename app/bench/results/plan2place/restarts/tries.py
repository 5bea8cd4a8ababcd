"""Every try of a solve from another random state on the `dense` diagnosis plans (20 x 2 seeds), Plan2Place without
restarts first, then, where it leaves an object out, three tries from salts 1-3 in three forms: the whole solve
(`full`: steps, repairs, second solves, as models.placement.restarts runs it), the same without the broken-first
solve (`no_reorder`: models.placement.reorder.ROUNDS = 0) and only the steps and repairs (`cheap`); each with its
time, objects placed, task objects out of reach and energy. `policies.py` then replays how
many tries to make and which to keep, without solving again. Writes `tries-dense.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/restarts/tries.py
"""
import json
import time
from pathlib import Path

import numpy as np

from app.bench.gates import diagnosis_plans
from models.placement import blas, reorder, restarts
from models.placement.greedy import _solved, _steps
from models.placement.plan2place import policy
from models.placement.polish import Standing
from models.placement.reach_kept import out_of_reach
from models.placement.repair import repair
from models.placement.restarts import drawn, salted


def first_solve(plan, seed):
    """Plan2Place's episode without restarts, its time, and the `choose` it placed with."""
    got, stepwise = {}, policy.place_stepwise

    def keeping_choose(plan, rng, choose, *rest):
        """`place_stepwise`, remembering the `choose` that `policy.place` builds inside."""
        got["choose"] = choose
        return stepwise(plan, rng, choose, *rest)

    policy.place_stepwise = keeping_choose
    try:
        t = time.perf_counter()
        weights = policy.shipped_weights()
        ep = policy.place(policy.shipped_policy(), plan, np.random.default_rng(seed), weights.use_global)
        return ep, time.perf_counter() - t, got["choose"]
    finally:
        policy.place_stepwise = stepwise


def summary(ep, t: float) -> dict:
    return {"t": t, "placed": len(ep.placed), "out": out_of_reach(ep), "E": Standing(ep).energy,
            "failed": len(ep.failed)}


def tries(plan, seed: int, choose) -> dict:
    start, out = np.random.default_rng(seed), {"full": [], "no_reorder": [], "cheap": []}
    with blas.one_blas_thread():
        for salt in (1, 2, 3):
            t = time.perf_counter()
            ep = _solved(plan, salted(start, salt), drawn(choose), None, None, True, True)
            out["full"].append(summary(ep, time.perf_counter() - t))
            reorder.ROUNDS, rounds = 0, reorder.ROUNDS
            t = time.perf_counter()
            ep = _solved(plan, salted(start, salt), drawn(choose), None, None, True, True)
            out["no_reorder"].append(summary(ep, time.perf_counter() - t))
            reorder.ROUNDS = rounds
            t = time.perf_counter()
            ep = _steps(plan, salted(start, salt), drawn(choose), None, None, ())
            repair(ep, None)
            out["cheap"].append(summary(ep, time.perf_counter() - t))
    return out


if __name__ == "__main__":
    restarts.RESTARTS, rows = 0, []
    for plan in diagnosis_plans("dense", 20):
        for seed in range(2):
            ep, t0, choose = first_solve(plan, seed)
            rows.append({"plan": plan.id, "seed": seed, "t0": t0, "base": summary(ep, t0),
                         **(tries(plan, seed, choose) if ep.failed else {"full": [], "no_reorder": [], "cheap": []})})
            print(plan.id, seed, rows[-1]["base"], flush=True)
    (Path(__file__).parent / "tries-dense.json").write_text(json.dumps(rows))
