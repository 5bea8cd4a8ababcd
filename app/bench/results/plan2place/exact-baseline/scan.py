"""How far the polish's baseline energy (ep.energy, fast navigation term) is from the exact energy of the layout
the polish starts from; and does the exact energy rise across the polish. Off-sample plans (i % step == step//2)."""
import sys
import models.placement.repair as rep
from models.datasets import load_dataset
from models.energy.exact import layout_energy
from models.placement.base import get_solver
from models.values import Placement

rows = []
orig = rep.polish
def spy(ep, observer=None):
    def exact():
        pl = [Placement(id=p.id, type=ep.problem.plan.object(p.id).type, x=p.x, z=p.z, rotation=p.rotation,
                        size=ep.problem.plan.object(p.id).size) for p in ep.placed]
        return layout_energy(ep.problem.plan, pl, ep.problem).total
    before_fast, before = ep.energy, exact()
    moved = orig(ep, observer)
    rows.append((before_fast, before, exact(), len(moved)))
    return moved
rep.polish = spy
n = int(sys.argv[1])
for ds in sys.argv[2:]:
    recs = load_dataset(ds, "validation" if ds == "seen" else None)
    step = max(len(recs) // 20, 1)
    off = [r for i, r in enumerate(recs) if i % step == step // 2][:n]
    for solver in ("greedy", "plan2place"):
        rows.clear()
        sol = get_solver(solver)
        for i, r in enumerate(off):
            sol.solve(r.plan, seed=i % 2)
        diffs = [f - e for f, e, _, _ in rows]
        rise = sum(a > e + 1e-9 for _, e, a, m in rows if m)
        print(ds, solver, "n", len(rows), "fast>exact", sum(d > 1e-9 for d in diffs), "fast<exact", sum(d < -1e-9 for d in diffs),
              "max|d| %.4f" % max(map(abs, diffs)), "polished", sum(m > 0 for *_, m in rows), "exact rose", rise, flush=True)
