"""A probe, nothing changed: in the small rooms where the exact finish ran and kept nothing, would Z3 asked again from
another random seed find a layout the finish keeps? Z3's layout depends on its seed; on `human` rooms where the Z3
baseline meets every constraint at an energy of 0, the finish's seed got a layout walling a task object off.
Replays Plan2Place on the placement bench's stored runs of at most 9 objects, every object placed, 60-99 % of the
constraints met; where the finish keeps nothing, solves the room again with up to `TRIES` other seeds (drawn from the
finish's) by the finish's own rule (`exact_finish` with a changed seed), noting which try is kept and each solve's
seconds. The placer is unchanged. probe.json is of the bench's runs stored at 06557f1 (before the retries shipped).
PYTHONPATH=. python app/bench/results/plan2place/z3-retry/probe.py  (writes probe.json beside it)"""

import json
import time
from pathlib import Path

import numpy as np

from app.bench.gates import finish_runs
from models.placement import exact_finish
from models.placement.base import get_solver
from models.placement.polish import Standing

HERE = Path(__file__).parent
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
TRIES = 3
finish = exact_finish.finished_exactly
records: list[dict] = []


def why(ep, seed) -> str:
    """Why the finish at `seed` keeps nothing: Z3 left an object out, walled a task object off, or its energy is
    not lower (or "kept")."""
    new = exact_finish.z3_episode(ep, seed)
    if new is None:
        return "unplaced"
    now, then = Standing(new), Standing(ep)
    return "out" if now.out > then.out else "energy" if now.energy >= then.energy else "kept"


def watched(ep, seed, observer=None, min_met=exact_finish.MIN_MET):
    out = finish(ep, seed, observer, min_met)
    if out is ep and exact_finish.wanted(ep, min_met) and exact_finish.small(ep.problem.plan, len(ep.problem.fixed)):
        rec = {"set": current, "plan": ep.problem.plan.id, "seed": bench_seed, "objects": len(ep.placed), "tries": []}
        start = time.perf_counter()
        rec["first"] = why(ep, seed)
        rec["first_s"] = time.perf_counter() - start
        for s in np.random.default_rng(seed).integers(2**31, size=TRIES):
            start = time.perf_counter()
            rec["tries"].append((why(ep, int(s)), time.perf_counter() - start))
        records.append(rec)
        print(rec, flush=True)
    return out


exact_finish.finished_exactly = watched
exact_finish.TRIES = 1  # the finish as it shipped when the probe ran: one solve
for current in SETS:
    for plan, bench_seed in finish_runs(current):
        get_solver("plan2place").solve(plan, seed=bench_seed)
(HERE / "probe.json").write_text(json.dumps(records, indent=1) + "\n")
