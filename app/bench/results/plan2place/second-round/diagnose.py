"""Diagnosis (16 diagnosis plans per set x 2 seeds, never the bench's or fresh plans): a second polish round over
every object still broken (`two`), and one that skips the objects whose first-round try came after the round's last
move (`skip`), against one round; Plan2Place, the three in turn.

    PYTHONPATH=. python app/bench/results/plan2place/second-round/diagnose.py > diagnose.md
"""
import sys
import time
from pathlib import Path

import numpy as np
import models.placement.repair as repair_mod
from models.placement.polish import Standing, _relocation, broken, polish
from app.bench.paired import cell, fingerprint, header, interval, paired
from app.bench.placement import score
from models.placement.base import get_solver
sys.path.insert(0, str(Path(__file__).parents[1] / "lookahead-bound"))
from run import diagnosis_plans

SETS = ("seen", "human", "unseen_a", "unseen_b", "dense")
METRICS = (("constraint_satisfaction", 100, True, 2), ("realism", 100, True, 2), ("key_nav", 100, True, 2),
           ("cnt", 100, True, 2), ("energy", 1, False, 3), ("ms", 1, False, 2))
TRIES = {"n": 0}

def one_round(ep, observer, only=None):
    moved, now, tried, last = [], Standing(ep), [], -1
    for oid in broken(ep):
        if only is not None and oid not in only:
            continue
        tried.append(oid)
        TRIES["n"] += 1
        move = _relocation(ep, now, oid)
        if move is None:
            continue
        last = len(tried) - 1
        now.moved(move)
        moved += [s.object_id for s in move.steps]
        for step in move.steps if observer is not None else ():
            observer(step)
    return moved, set(tried[:last + 1])

def twice(ep, observer=None):
    moved, _ = one_round(ep, observer)
    return moved + (one_round(ep, observer)[0] if moved else [])

def twice_skip(ep, observer=None):
    moved, unsettled = one_round(ep, observer)
    return moved + (one_round(ep, observer, unsettled)[0] if moved else [])

VARIANTS = {"one": lambda ep, o=None: one_round(ep, o)[0], "two": twice, "skip": twice_skip}
rows, tries = [], {v: 0 for v in VARIANTS}
solver = get_solver("plan2place")
k = 0
for ds in SETS:
    for plan in diagnosis_plans(ds, 16):
        for seed in (0, 1):
            k += 1
            names = list(VARIANTS)
            for v in names[k % 3:] + names[:k % 3]:
                repair_mod.polish = VARIANTS[v]
                TRIES["n"] = 0
                t = time.perf_counter()
                layout = solver.solve(plan, seed=seed)
                ms = 1000 * (time.perf_counter() - t) / len(plan.objects)
                tries[v] += TRIES["n"]
                got = score(plan, layout)
                rows.append({"set": ds, "plan": plan.id, "seed": seed, "solver": v, "ms": ms, "fp": fingerprint(layout), **{m: got.get(m) for m, *_ in METRICS if m != "ms"}})
    print(ds, file=sys.stderr, flush=True)
rng = np.random.default_rng(0)
print("\n".join(header("set / variant - one", METRICS)))
for ds in SETS:
    mine = [r for r in rows if r["set"] == ds]
    for v in ("two", "skip"):
        print(f"| {ds} / {v} | " + " | ".join(cell(*(sc * x for x in interval(paired(mine, m, v, "one"), rng)), up, d) for m, sc, up, d in METRICS) + " |")
for ds in SETS:
    mine = [r for r in rows if r["set"] == ds]
    two = {(r["plan"], r["seed"]): r["fp"] for r in mine if r["solver"] == "two"}
    same = sum(two[(r["plan"], r["seed"])] == r["fp"] for r in mine if r["solver"] == "skip")
    print(ds, {v: round(float(np.median([r["ms"] for r in mine if r["solver"] == v])), 2) for v in VARIANTS}, "skip layouts equal to two:", same, "of", len(two))
print("relocations tried:", tries)
