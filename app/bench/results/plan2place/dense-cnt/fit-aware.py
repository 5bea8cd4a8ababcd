"""Prototype: in crowded rooms, among the policy's K most probable candidates that keep reach, take the one after
which the most objects still to come have a legal pose (then the policy's order)."""
import sys, time, json
import numpy as np
sys.path.insert(0, "app/bench/results/plan2place/lookahead-bound")
from run import diagnosis_plans
from models.placement import greedy as G
from models.placement.polish import crowded
from models.placement.base import get_solver
from app.bench.placement import score
K = int(sys.argv[2]); MODE = sys.argv[3]; n = int(sys.argv[1])
plans = diagnosis_plans("dense", n)
orig = G.Episode.guarded
def fits(ep, opts, k, rest):
    pose = ep.scorer.place(opts.obj, *(float(v) for v in opts.cands[opts.feasible[k]]))
    placed = [*ep.placed, pose]
    c = 0
    for o in rest:
        cands, _ = ep.scorer.bodies(o)
        ok, _ = G.hard_filter(ep.scorer, o, placed, cands, ep.scorer.swept(o), False)
        c += bool(ok.any())
    return c
def guarded(self, opts, order):
    if MODE == "off" or not crowded(self.problem.plan):
        return orig(self, opts, order)
    top = self.first_kept(opts, order, K)
    rest = [o for o in self.order[self.i + 1:] if o.id not in self.problem.fixed]
    if MODE == "big":
        rest = sorted(rest, key=lambda o: -o.size.x * o.size.z)[:3]
    if len(top) == 1 or not rest:
        return int(top[0])
    f = [fits(self, opts, int(k), rest) for k in top]
    return int(top[int(np.argmax(f))])
G.Episode.guarded = guarded
s = get_solver("plan2place")
rows = []
t0 = time.perf_counter(); objs = 0
for seed in (0, 1):
    for p in plans:
        lay = s.solve(p, seed=seed); objs += len(p.objects)
        m = score(p, lay); rows.append({k: m[k] for k in ("cnt", "key_nav", "constraint_satisfaction", "energy", "realism") if k in m})
print(MODE, K, "ms/obj", round(1000 * (time.perf_counter() - t0) / objs, 1))
for k in rows[0]:
    v = [r[k] for r in rows if r[k] is not None]
    print(k, round(float(np.mean(v)), 4))
