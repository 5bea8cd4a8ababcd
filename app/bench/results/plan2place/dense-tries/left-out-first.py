"""Tried for `dense`, not kept: a second Plan2Place episode with the objects the first left out placed first, on 20
dense plans off the benchmark sample (PYTHONPATH=. python app/bench/results/plan2place/dense-tries/left-out-first.py dense 20)."""
import sys, time
import numpy as np
from models.datasets import load_dataset
from models.placement import greedy as G
from models.placement.problem import PlacementProblem
from models.placement.plan2place.policy import place, shipped_policy, shipped_weights
ds = sys.argv[1] if len(sys.argv) > 1 else "dense"
recs = load_dataset(ds, "validation" if ds == "seen" else None)
step = max(len(recs) // 20, 1)
off = [r for i, r in enumerate(recs) if i % step == step // 2][:int(sys.argv[2]) if len(sys.argv) > 2 else 12]
orig = PlacementProblem.from_plan.__func__
FIRST = []
def from_plan(cls, plan, fixed=None):
    p = orig(cls, plan, fixed)
    if FIRST:
        p.order = [o for o in p.order if o.id in FIRST] + [o for o in p.order if o.id not in FIRST]
    return p
PlacementProblem.from_plan = classmethod(from_plan)
pol, ug = shipped_policy(), shipped_weights().use_global
a = b = 0; ta = tb = 0.0
for r in off:
    FIRST.clear()
    t = time.perf_counter(); ep = place(pol, r.plan, np.random.default_rng(0), ug); ta += time.perf_counter() - t
    out1 = set(ep.failed)
    a += len(out1)
    if out1:
        FIRST.extend(sorted(out1))
        t = time.perf_counter(); ep2 = place(pol, r.plan, np.random.default_rng(0), ug); tb += time.perf_counter() - t
        out2 = set(ep2.failed)
        better = len(out2) < len(out1)
        b += len(out2) if better else len(out1)
        print(len(r.plan.objects), "first", sorted(out1), "retry", sorted(out2), "superset" if better and not (out2 - out1) else "", round(ep.energy, 2), round(ep2.energy, 2))
    FIRST.clear()
print("left out: once", a, "with retry", b, "s first", round(ta, 1), "retry", round(tb, 1))
