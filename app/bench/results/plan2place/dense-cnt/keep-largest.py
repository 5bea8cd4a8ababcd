"""Prototype (not shipped; LOG.md): the guard also keeps the largest object still to come placeable: if the most wanted
(reach-kept) pick leaves it no legal pose, take the first of the next K reach-kept candidates that does. Run from a
tree's root, one mode per process: PYTHONPATH=. python app/bench/results/plan2place/dense-cnt/keep-largest.py on|off
human,dense,unseen_a"""
import sys, time
import numpy as np
sys.path.insert(0, "app/bench/results/plan2place/lookahead-bound")
from run import diagnosis_plans
from models.datasets import load_dataset
from models.placement import greedy as G
from models.placement.base import get_solver
from app.bench.placement import score
K = 8
orig = G.Episode.guarded
def fits(ep, opts, k, big):
    pose = ep.scorer.place(opts.obj, *(float(v) for v in opts.cands[opts.feasible[k]]))
    cands, _ = ep.scorer.bodies(big)
    ok, _ = G.hard_filter(ep.scorer, big, [*ep.placed, pose], cands, ep.scorer.swept(big), False)
    return bool(ok.any())
def guarded(self, opts, order):
    pick = orig(self, opts, order)
    rest = [o for o in self.order[self.i + 1:] if o.id not in self.problem.fixed]
    if not rest:
        return pick
    big = max(rest, key=lambda o: o.size.x * o.size.z)
    if fits(self, opts, pick, big):
        return pick
    cands, _ = self.scorer.bodies(big)
    ok, _ = G.hard_filter(self.scorer, big, self.placed, cands, self.scorer.swept(big), False)
    if not ok.any():
        return pick  # it has no room already: nothing to keep
    for k in self.first_kept(opts, order, K):
        if fits(self, opts, int(k), big):
            return int(k)
    return pick
MODE = sys.argv[1]
if MODE == "on":
    G.Episode.guarded = guarded
s = get_solver("plan2place")
for ds in sys.argv[2].split(","):
    plans = [r.plan for r in load_dataset("human")] if ds == "human" else diagnosis_plans(ds, 20)
    rows, t0, objs = [], time.perf_counter(), 0
    for p in plans:
        for seed in (0, 1):
            lay = s.solve(p, seed=seed); objs += len(p.objects)
            m = score(p, lay); rows.append((p.id, seed, m, tuple((q.id, q.x, q.z, q.rotation) for q in lay.placements)))
    ms = 1000 * (time.perf_counter() - t0) / objs
    print(MODE, ds, f"ms/obj {ms:.1f}", {k: round(float(np.mean([r[2][k] for r in rows if r[2][k] is not None])), 4) for k in ("cnt", "key_nav", "constraint_satisfaction", "energy", "realism")}, flush=True)
