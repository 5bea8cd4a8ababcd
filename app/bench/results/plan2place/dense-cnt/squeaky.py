"""Does solving again with the left-out objects first place more on `dense` without losing reach? After a Plan2Place
solve that leaves objects out, up to `ROUNDS` more solves, each with every object left out so far placed first
(`front`: before all others; `topo`: first among the objects whose relation targets are placed), keeping a new layout
if the acceptance rule prefers it to the best so far: `reach`, more objects placed and no fewer task objects reached
(or as many placed and more reached); `reach+constraints`, that and no fewer constraints met; `reach+energy`, that and
a lower energy. On the 20 `dense` diagnosis plans x 2 seeds (never the bench's or fresh plans). Run from a tree's root:

    PYTHONPATH=. python app/bench/results/plan2place/dense-cnt/squeaky.py > app/bench/results/plan2place/dense-cnt/squeaky.txt
"""
import sys
import time
from pathlib import Path

import numpy as np

from app.bench.placement import score
from models.placement import problem as PB
from models.placement.base import get_solver

sys.path.insert(0, str(Path(__file__).parent.parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

FIRST: list[str] = []  # the ids to place first
MODE = {"order": "front"}
SHIPPED = PB.PlacementProblem.from_plan.__func__


def from_plan(cls, plan, fixed=None):
    """The shipped problem with `FIRST` moved ahead in its order, as `MODE` says."""
    pb = SHIPPED(cls, plan, fixed)
    if not FIRST:
        return pb
    if MODE["order"] == "front":
        order = [o for o in pb.order if o.id in FIRST] + [o for o in pb.order if o.id not in FIRST]
    else:
        remaining, pos = {o.id: o for o in pb.order}, {o.id: k for k, o in enumerate(pb.order)}
        deps = {o.id: {c.target for c in pb.constraints.objects[o.id].relations if c.target in remaining}
                for o in pb.order}
        order = []
        while remaining:
            ready = [o for i, o in remaining.items() if not (deps[i] & remaining.keys())]
            pick = min(ready or remaining.values(), key=lambda o: (o.id not in FIRST, pos[o.id]))
            order.append(pick)
            del remaining[pick.id]
    pb.order = [o for o in order if o.id in pb.fixed] + [o for o in order if o.id not in pb.fixed]
    return pb


PB.PlacementProblem.from_plan = classmethod(from_plan)


def judged(plan, layout) -> tuple[int, int, dict]:
    sc = score(plan, layout)
    tasks = sum(o.is_task for o in plan.objects)
    return len(plan.objects) - len(layout.unplaced), round((sc["key_nav"] or 0) * tasks), sc


def better(new, best, rule: str) -> bool:
    ok = (new[0] > best[0] and new[1] >= best[1]) or (new[0] >= best[0] and new[1] > best[1])
    if rule == "reach+constraints":
        ok = ok and new[2]["constraint_satisfaction"] >= best[2]["constraint_satisfaction"] - 1e-9
    if rule == "reach+energy":
        ok = ok and new[2]["energy"] < best[2]["energy"]
    return ok


def run(plans, solver, rounds: int, rule: str) -> None:
    base, kept, t_base, t_more, changed = [], [], 0.0, 0.0, 0
    for plan in plans:
        for seed in (0, 1):
            FIRST.clear()
            t = time.process_time()
            layout = solver.solve(plan, seed=seed)
            t_base += time.process_time() - t
            best = first = judged(plan, layout)
            t = time.process_time()
            for _ in range(rounds):
                if best[0] == len(plan.objects):
                    break
                FIRST.extend(u.id for u in layout.unplaced if u.id not in FIRST)
                layout = solver.solve(plan, seed=seed)
                if better(new := judged(plan, layout), best, rule):
                    best = new
            t_more += time.process_time() - t
            changed += best is not first
            base.append(first[2]), kept.append(best[2])
    for name, rows in (("shipped", base), (f"{MODE['order']}, {rounds} round(s), {rule}", kept)):
        mean = lambda k, f=100: f * float(np.mean([r[k] for r in rows if r[k] is not None]))  # noqa: E731
        print(f"{name}: CNT {mean('cnt'):.2f}, Key_NAV {mean('key_nav'):.2f}, constraints {mean('constraint_satisfaction'):.2f}, "
              f"energy {mean('energy', 1):.3f}, realism {mean('realism'):.2f}")
    print(f"  layouts changed {changed} of {len(kept)}; CPU s: the solves {t_base:.1f}, the solves again {t_more:.1f}",
          flush=True)


if __name__ == "__main__":
    plans = diagnosis_plans("dense", 20)
    solver = get_solver("plan2place")
    solver.solve(plans[0], seed=0)
    for order, rounds, rule in [("front", 1, "reach"), ("front", 3, "reach"), ("topo", 3, "reach"),
                                ("topo", 3, "reach+constraints"), ("topo", 3, "reach+energy")]:
        MODE["order"] = order
        run(plans, solver, rounds, rule)
