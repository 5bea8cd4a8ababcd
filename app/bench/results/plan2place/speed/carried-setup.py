"""The repairs' energy set-up carried from pass to pass, in-process A/B on a set's bench plans (2 seeds), the two
variants alternating: `old`, each pass (and each polish round) took the episode's last step's set-up if it was of the
layout, else built a fresh one; `new`, it takes the one the last repair move or pass left (`Episode.repaired`). Prints
CPU time per object, how many full set-ups were built fresh, and whether the layouts are the same. Run from a tree's
root:
PYTHONPATH=. python app/bench/results/plan2place/speed/carried-setup.py dense 20 6   (set, plans, rounds)"""
import sys
import time
from functools import cached_property

import numpy as np

from app.bench.plan2place import pick_records
from models.energy.vectorised import CandidateEnergy
from models.placement import polish as P
from models.placement.base import get_solver

new_setup, new_moved = P.Standing.__dict__["setup"].func, P.Standing.moved


def old_setup(self):
    """The code before: the last move's set-up of this pass, else the episode's last step's, else a fresh one."""
    if self.__dict__.get("_next") is not None:
        return self._next()
    last = self.ep.setup
    if [P._key(p) for p in last.placed] == [P._key(p) for p in self.ep.placed]:
        return last
    return CandidateEnergy(self.ep.problem, self.ep.placed)


def old_moved(self, move):
    new_moved(self, move)
    self.ep.repaired, self.__dict__["_next"] = None, move.setup


def use(v):
    P.Standing.setup = cached_property(old_setup if v == "old" else new_setup)
    P.Standing.setup.__set_name__(P.Standing, "setup")
    P.Standing.moved = old_moved if v == "old" else new_moved


ds, n, reps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
plans = [r.plan for r in pick_records(ds, n)]
s = get_solver("plan2place")
s.solve(plans[0], seed=0)
fresh, init = {"n": 0}, CandidateEnergy.__init__


def counted(self, problem, placed, *a, **k):
    fresh["n"] += bool(placed)
    init(self, problem, placed, *a, **k)


CandidateEnergy.__init__ = counted
tot, lay = {"old": [], "new": []}, {}
for r in range(reps):
    for v in ("old", "new") if r % 2 == 0 else ("new", "old"):
        use(v)
        fresh["n"], objs, out, t = 0, 0, [], time.process_time()
        for seed in range(2):
            for p in plans:
                layout = s.solve(p, seed=seed)
                objs += len(p.objects)
                out.append([(q.id, q.x, q.z, q.rotation) for q in layout.placements])
        tot[v].append(1000 * (time.process_time() - t) / objs)
        lay.setdefault(v, out)
        assert lay[v] == out
        print(v, round(tot[v][-1], 2), "ms/obj (CPU)", fresh["n"], "full set-ups built", flush=True)
print(ds, "same layouts:", lay["old"] == lay["new"], {v: round(float(np.median(x)), 2) for v, x in tot.items()},
      "new/old per pair:", [round(b / a, 3) for a, b in zip(tot["old"], tot["new"])])
