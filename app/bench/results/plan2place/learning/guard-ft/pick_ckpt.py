"""Checkpoint selection on off-sample plans (16 per set, not the bench's; 2 seeds): mean final energy, Key_NAV,
constraints, realism per set for greedy, the untrained network and each run."""
import sys, statistics
from app.bench.plan2place import solver_for, evaluate
from app.bench.placement import pick_records
from models.datasets import load_dataset
from models.placement.base import get_solver
runs = sys.argv[1].split(","); sets = sys.argv[2].split(",") if len(sys.argv) > 2 else ["seen", "unseen_a", "unseen_b", "dense", "human"]
solvers = [get_solver("greedy"), get_solver("plan2place_untrained")] + [solver_for(r) for r in runs]
print("| solver | " + " | ".join(sets) + " |\n|" + " --- |" * (len(sets) + 1))
res = {}
for ds in sets:
    recs = load_dataset(ds, "validation" if ds == "seen" else None); k = max(len(recs) // 20, 1)
    bench = {r.plan.id for n in ((20, 40) if ds == 'seen' else (20,)) for r in pick_records(ds, n)}
    plans = [r.plan for i, r in enumerate(recs) if i % k == k // 2 and r.plan.id not in bench][:16]
    rows = evaluate(solvers, plans, 2)
    for name, rs in rows.items():
        m = lambda key: statistics.mean([r[key] for r in rs if r.get(key) is not None])
        res.setdefault(name, []).append(f"{m('energy'):.3f} / {100*m('key_nav'):.1f} / {100*m('constraint_satisfaction'):.1f} / {100*m('realism'):.1f}")
for name, cells in res.items():
    print(f"| {name} | " + " | ".join(cells) + " |")
