"""Where the polish's time goes in crowded rooms: the time inside `_relocation` per round and outcome (a move found
or none), on a set's bench plans x 2 seeds, in ms per object of the whole solve. Run from a tree's root:
PYTHONPATH=. python app/bench/results/plan2place/speed/refused-moves.py dense 20"""
import sys, time, collections
import numpy as np
from app.bench.plan2place import pick_records
from models.placement import polish as P
from models.placement.base import get_solver
ds = sys.argv[1]; n = int(sys.argv[2])
plans = [r.plan for r in pick_records(ds, n)]
s = get_solver("plan2place"); s.solve(plans[0], seed=0)
state = {"round": 0}
T = collections.Counter(); C = collections.Counter(); M = collections.Counter()
orig_round = P._round
def rnd(ep, obs, moved, tried):
    state["round"] += 1
    return orig_round(ep, obs, moved, tried)
P._round = rnd
orig_polish = P.polish
def pol(ep, observer=None):
    state["round"] = 0
    return orig_polish(ep, observer)
P.polish = pol
import models.placement.repair as R
R.polish = pol
orig = P._relocation
def g(ep, now, oid):
    t = time.perf_counter(); m = orig(ep, now, oid); dt = time.perf_counter() - t
    r = state["round"]; T[r, m is not None] += dt; C[r, m is not None] += 1
    return m
P._relocation = g
objs = 0; t0 = time.perf_counter()
for seed in range(2):
    for p in plans:
        s.solve(p, seed=seed); objs += len(p.objects)
print(ds, f"solve ms/obj {1000 * (time.perf_counter() - t0) / objs:.2f}")
for k in sorted(T): print("round", k[0], "moved" if k[1] else "none", C[k], f"ms/obj {1000*T[k]/objs:.2f}")
