"""Time per object of Plan2Place on a set's bench plans (2 seeds), split by repair pass. Run from a tree's root:
PYTHONPATH=. python app/bench/results/plan2place/speed/passes.py unseen_a 20   (add --prof for cProfile)"""
import sys, time, cProfile, pstats
import numpy as np
from app.bench.plan2place import pick_records
from models.placement import repair as R, habits as H, polish as P
from models.placement.base import get_solver
ds = sys.argv[1]; n = int(sys.argv[2]) if len(sys.argv) > 2 else 20
plans = [r.plan for r in pick_records(ds, n)]
s = get_solver("plan2place"); s.solve(plans[0], seed=0)
tot = {}
def wrap(mod, name):
    f = getattr(mod, name)
    def g(*a, **k):
        t = time.perf_counter(); r = f(*a, **k); tot[name] = tot.get(name, 0) + time.perf_counter() - t; return r
    setattr(mod, name, g)
for name in ("make_room", "restore_access", "polish", "regroup", "keep_companions"):
    wrap(R, name)
objs = 0; t0 = time.perf_counter()
pr = cProfile.Profile() if "--prof" in sys.argv else None
if pr: pr.enable()
for seed in range(2):
    for p in plans:
        s.solve(p, seed=seed); objs += len(p.objects)
if pr: pr.disable()
T = time.perf_counter() - t0
print(ds, "ms/obj total", round(1000*T/objs, 2), {k: round(1000*v/objs, 2) for k, v in tot.items()})
if pr: pstats.Stats(pr).sort_stats("cumulative").print_stats(*[int(a) if a.isdigit() else a for a in sys.argv[sys.argv.index("--prof") + 1:]] or [45])
