"""Would one more polish round after the group moves and the companions' pass meet more constraints, and at what
cost? The round takes the objects still broken that were tried before the last move (the polish's own rule: one tried
with nothing moved since is passed over), in every room. Plan2Place with and without it, alternating, on 16 diagnosis
plans per set x 2 seeds (never the bench's or fresh plans); prints the mean difference (with - without) and the CPU
time of both. Run from a tree's root:

    PYTHONPATH=. python app/bench/results/plan2place/polish-again/run.py > app/bench/results/plan2place/polish-again/run.txt
"""
import sys
import time
from pathlib import Path

import numpy as np

from app.bench.paired import fingerprint
from app.bench.placement import score
from models.placement import polish as P
from models.placement import repair as R
from models.placement.base import get_solver
from models.placement.groups import regroup
from models.placement.habits import keep_companions

sys.path.insert(0, str(Path(__file__).parent.parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
ON = {"again": False}
COUNT = {"tries": 0, "moves": 0}


def polish(ep, observer=None):
    """The shipped polish, keeping its `tried` and `moved` on the episode for the round after the later passes."""
    moved, tried = [], {}
    for _ in range(2 if P.crowded(ep.problem.plan) else 1):
        if not P._round(ep, observer, moved, tried):
            break
    ep.__dict__["_polish_state"] = tried, moved
    return moved


def repair(ep, observer=None):
    """The shipped passes in their order, then, with ON["again"], the polish's round once more."""
    done = R.make_room(ep, observer) + R.restore_access(ep, observer) + polish(ep, observer)
    later = regroup(ep, observer) + keep_companions(ep, observer)
    if ON["again"]:
        tried, moved = ep._polish_state
        moved += later
        start = len(moved)
        COUNT["tries"] += sum(1 for oid in P.broken(ep) if tried.get(oid) != len(moved))
        P._round(ep, observer, moved, tried)
        COUNT["moves"] += len(moved) - start
        later += moved[start:]
    return done + later


R.repair = repair

if __name__ == "__main__":
    solver = get_solver("plan2place")
    print("one more polish round after the group moves and the companions - without; 16 diagnosis plans x 2 seeds; "
          "metrics x 100, energy as is")
    for ds in SETS:
        plans = diagnosis_plans(ds, 16)
        solver.solve(plans[0], seed=0)
        rows, cpu, same = {False: [], True: []}, {False: 0.0, True: 0.0}, 0
        COUNT.update(tries=0, moves=0)
        for k, plan in enumerate(plans):
            for seed in (0, 1):
                prints = {}
                for again in ((False, True) if (k + seed) % 2 else (True, False)):
                    ON["again"] = again
                    t = time.process_time()
                    layout = solver.solve(plan, seed=seed)
                    cpu[again] += time.process_time() - t
                    rows[again].append(score(plan, layout))
                    prints[again] = fingerprint(layout)
                same += prints[False] == prints[True]
        diff = lambda m, f=100: f * float(np.mean([(b[m] or 0) - (a[m] or 0)  # noqa: E731
                                                   for a, b in zip(rows[False], rows[True])]))
        print(f"{ds}: layouts the same {same} of {len(rows[True])}; constraints {diff('constraint_satisfaction'):+.2f}, "
              f"energy {diff('energy', 1):+.4f}, Key_NAV {diff('key_nav'):+.2f}, realism {diff('realism'):+.2f}, "
              f"CNT {diff('cnt'):+.2f}; the round tried {COUNT['tries']} objects, moved {COUNT['moves']}; CPU s "
              f"{cpu[False]:.1f} -> {cpu[True]:.1f} ({100 * (cpu[True] / cpu[False] - 1):+.0f} %)", flush=True)
