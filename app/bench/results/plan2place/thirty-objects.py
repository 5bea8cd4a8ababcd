"""Plans of 28 or more objects, which no dataset holds (the largest `seen` plan has 26): the room planner's own
recipe with 22-28 context objects per room and rooms 1.6 times the usual size, on ALFRED valid_unseen tasks in four
room types. Plan2Place and DFS on each (seed 0): errors, objects neither placed nor given a reason, CNT, Key_NAV,
constraints and ms per object. With `--crowded` the same plans in rooms shrunk to `CROWDED` of their width and
depth (objects covering 50-85 % of the floor, more than `dense`'s rooms), where objects are left out. Run from a
tree's root:
PYTHONPATH=. python app/bench/results/plan2place/thirty-objects.py > app/bench/results/plan2place/thirty-objects.txt
PYTHONPATH=. python app/bench/results/plan2place/thirty-objects.py --crowded > \
    app/bench/results/plan2place/thirty-objects-crowded.txt
"""

import random
import statistics
import sys
import time

from app.bench.placement import score
from models.language.alfred import load_annotations
from models.placement.base import get_solver
from models.planning import ConstraintWriter, RoomPlanner
from models.planning.room_planner import RoomPlannerSettings

LARGE = RoomPlannerSettings(min_context=22, max_context=28, size_scale=1.6)
PLANS, AT_LEAST = 12, 28
CROWDED = 0.7  # --crowded: each room's width and depth scaled by this, doors and windows along with them


def large_plans() -> list:
    planner, writer, rng, plans = RoomPlanner(LARGE), ConstraintWriter(), random.Random(7), []
    for k, row in enumerate(load_annotations("valid_unseen")):
        for room in ("living room", "kitchen", "bedroom", "bathroom"):
            graph = row.task_graph().model_copy(update={"room_type": room})
            plan = writer.write(planner.plan(graph, seed=rng.randrange(2**31), plan_id=f"large-{k}-{room}"))
            if len(plan.objects) >= AT_LEAST:
                plans.append(plan)
            if len(plans) == PLANS:
                return plans
    return plans


def shrunk(plan):
    """`plan` in a room `CROWDED` times as wide and deep, its openings moved along."""
    room = plan.room
    doors, windows = ([o.model_copy(update={"center": o.center * CROWDED}) for o in openings]
                      for openings in (room.doors, room.windows))
    return plan.model_copy(update={"room": room.model_copy(update={
        "width": room.width * CROWDED, "depth": room.depth * CROWDED, "doors": doors, "windows": windows})})


def main() -> None:
    plans = large_plans()
    if "--crowded" in sys.argv:
        plans = [shrunk(p) for p in plans]
        cover = [sum(o.size.x * o.size.z for o in p.objects) / (p.room.width * p.room.depth) for p in plans]
        print(f"in rooms {CROWDED} times as wide and deep: objects cover {min(cover):.0%}-{max(cover):.0%} of the floor")
    print(f"{len(plans)} plans of {min(len(p.objects) for p in plans)}-{max(len(p.objects) for p in plans)} objects")
    for name in ("dfs", "plan2place"):
        solver, rows, errors, silent = get_solver(name), [], 0, 0
        for plan in plans:
            t = time.perf_counter()
            try:
                layout = solver.solve(plan, seed=0)
            except Exception as e:  # counted: the point of the run
                errors += 1
                print(f"  {name} {plan.id}: {type(e).__name__}: {e}")
                continue
            ms = 1000 * (time.perf_counter() - t) / len(plan.objects)
            placed, reasons = {p.id for p in layout.placements}, {u.id: u.reason for u in layout.unplaced}
            silent += sum(o.id not in placed and not reasons.get(o.id) for o in plan.objects)
            rows.append({"ms": ms, **score(plan, layout)})
        mean = {m: 100 * statistics.mean(r[m] for r in rows if r[m] is not None)
                for m in ("cnt", "key_nav", "constraint_satisfaction")}
        print(f"  {name:10s} errors {errors}, objects neither placed nor reasoned {silent}; CNT {mean['cnt']:.1f}, "
              f"Key_NAV {mean['key_nav']:.1f}, constraints {mean['constraint_satisfaction']:.1f}; ms per object p50 "
              f"{statistics.median(r['ms'] for r in rows):.1f}, worst {max(r['ms'] for r in rows):.1f}")


if __name__ == "__main__":
    main()
