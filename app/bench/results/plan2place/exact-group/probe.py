"""A probe, nothing built: where Plan2Place ends with a constraint broken, could an exact solver re-place just the
objects of the broken constraints (and their relations' targets), every other object kept where it stands?

For each run of Plan2Place (the bench's plans, seeds 0..k-1) that leaves a constraint broken, the MILP placer (HiGHS)
solves the plan with the other objects `fixed`, at budgets of 0.1, 0.3 and 1.0 s; a result would be kept under the
polish's conditions (no object dropped, a lower exact energy, Key_NAV no lower). One JSON line per run, then per
budget the runs kept, the constraints they would add per run and the mean time. Z3 is not tried: with every object
pinned it finds no model within 3 s on two of three `human` rooms (MILP's presolve answers at once).
PYTHONPATH=. python app/bench/results/plan2place/exact-group/probe.py human 40 3 > probe-human.txt"""

import json
import sys
import time

import numpy as np

from app.bench.placement import pick_records, score
from models.constraints.evaluate import Poses, placement, relation
from models.geometry import Footprint, gap, wall_clearance
from models.placement import get_solver
from models.placement.milp import MILPSolver
from models.placement.problem import PlacementProblem

BUDGETS = {"m10": 0.1, "m30": 0.3, "m100": 1.0}


def group(plan, layout) -> set[str]:
    """The objects of the broken constraints and their relations' targets."""
    problem, room = PlacementProblem.from_plan(plan), plan.room
    fps = {p.id: Footprint(p.x, p.z, p.size.x, p.size.z, p.rotation) for p in layout.placements}
    pose = {k: Poses.one(f.x, f.z, f.rotation, f.width, f.depth) for k, f in fps.items()}
    bad = set()
    for oid, oc in problem.constraints.objects.items():
        if oid not in fps:
            continue
        f = fps[oid]
        if not placement(oc.placement, pose[oid], room.width, room.depth,
                         clearance=np.array([wall_clearance(f, room.width, room.depth)]))[1][0]:
            bad.add(oid)
        for c in oc.relations:
            if c.target in fps and not relation(c.name, pose[oid], pose[c.target],
                                                gap=np.array([gap(f, fps[c.target])]))[1][0]:
                bad |= {oid, c.target}
    return bad | {c.target for oid in bad for c in problem.constraints.objects[oid].relations}


def main(ds: str, n: int, seeds: int) -> None:
    p2p, rows = get_solver("plan2place"), []
    for plan in (r.plan for r in pick_records(ds, n)):
        for seed in range(seeds):
            layout = p2p.solve(plan, seed=seed)
            s0 = score(plan, layout)
            if s0["constraint_satisfaction"] >= 1 - 1e-9:
                continue
            free = group(plan, layout)
            fixed = {p.id: (p.x, p.z, p.rotation) for p in layout.placements if p.id not in free}
            row = {"plan": plan.id, "seed": seed, "n": len(plan.objects), "group": len(free),
                   "cs0": round(s0["constraint_satisfaction"], 3), "e0": round(s0["energy"], 3), "kn0": s0["key_nav"]}
            for name, budget in BUDGETS.items():
                t = time.perf_counter()
                s1 = score(plan, MILPSolver().solve(plan, seed=seed, time_budget_s=budget, fixed=fixed))
                keep = s1["cnt"] >= s0["cnt"] and s1["energy"] < s0["energy"] - 1e-9 and s1["key_nav"] >= s0["key_nav"]
                row[name] = {"t": round(time.perf_counter() - t, 3), "cs": round(s1["constraint_satisfaction"], 3),
                             "e": round(s1["energy"], 3), "kn": s1["key_nav"], "cnt": s1["cnt"], "keep": keep}
            print(json.dumps(row), flush=True)
            rows.append(row)
    for name in BUDGETS:
        kept = [r for r in rows if r[name]["keep"]]
        print(f"{name}: kept {len(kept)} of {len(rows)} runs with a constraint broken; constraints "
              f"{100 * sum(r[name]['cs'] - r['cs0'] for r in kept) / max(len(rows), 1):+.2f} per such run; "
              f"mean {np.mean([r[name]['t'] for r in rows]):.3f} s")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
