"""Speed of the vectorised energy against the exact one, on the issue's reference workload.

A 5 m x 5 m room with 15 objects already placed (by DFS, seeded); the 16th object's candidates are
every pose on a 0.1 m grid in 4 rotations. The vectorised energy scores all of them at once (median
of 20 runs); the exact energy is timed on 200 of the same candidates and its per-candidate cost is
projected to all of them. The ratio is exact / vectorised for the same work. Also printed: the cost of
the vectorised energy's exact navigation mode, how often its fast mode's navigation term agrees, and the
per-step set-up for the placed objects: from scratch (the baseline) and incremental (`after`: one object added,
as each placer step does; `without`: one taken out, as the repairs do).
"""

from __future__ import annotations

import statistics
import time

import numpy as np

from models.energy.exact import layout_energy
from models.energy.vectorised import CandidateEnergy
from models.placement import PlacementProblem, get_solver
from models.placement.candidates import CandidateScorer
from models.values import ConstraintPlan, Placement

TYPES = [("Sofa", 2.0, 0.9), ("CoffeeTable", 1.0, 0.6), ("ArmChair", 0.8, 0.8), ("ArmChair", 0.8, 0.8),
         ("SideTable", 0.5, 0.5), ("SideTable", 0.5, 0.5), ("FloorLamp", 0.4, 0.4), ("TVStand", 1.4, 0.45),
         ("ShelvingUnit", 0.9, 0.4), ("Dresser", 1.2, 0.5), ("DiningTable", 1.2, 0.9), ("Chair", 0.45, 0.45),
         ("Chair", 0.45, 0.45), ("GarbageCan", 0.35, 0.3), ("HousePlant", 0.4, 0.4), ("Desk", 1.2, 0.6)]
ROLES = {0: "anchor", 7: "inference", 15: "inference"}


def reference_case():
    objects = [{"id": f"{t.lower()}-{i}", "type": t, "size": {"x": w, "y": 0.8, "z": d}, "role": ROLES.get(i, "context")}
               for i, (t, w, d) in enumerate(TYPES)]
    text = "\n".join([f"{objects[1]['id']} | middle | in front of, {objects[0]['id']}",
                      f"{objects[2]['id']} | middle | near, {objects[1]['id']} | face to, {objects[1]['id']}",
                      f"{objects[11]['id']} | middle | around, {objects[10]['id']}",
                      f"{objects[15]['id']} | edge | far, {objects[0]['id']}"])
    plan = ConstraintPlan.model_validate({"id": "energy-bench", "constraints": text, "objects": objects, "room": {
        "type": "living room", "width": 5.0, "depth": 5.0, "doors": [{"wall": "south", "center": 2.5, "width": 1.0}]}})
    placed_plan = plan.model_copy(update={"objects": plan.objects[:15]})
    layout = get_solver("dfs").solve(placed_plan, seed=0)
    return plan, layout.placements, plan.objects[15]


class _Pose:
    def __init__(self, p: Placement):
        self.id, self.x, self.z, self.rotation, self.width, self.depth = p.id, p.x, p.z, p.rotation, p.size.x, p.size.z


def main(args) -> int:
    plan, placed, obj = reference_case()
    problem = PlacementProblem.from_plan(plan)
    scorer = CandidateScorer(problem, step=0.1)
    cands = scorer.candidates(obj)
    energy = CandidateEnergy(problem, [_Pose(p) for p in placed])
    energy.score(obj, cands)  # warm-up
    runs = []
    for _ in range(20):
        t0 = time.perf_counter()
        energy.score(obj, cands)
        runs.append(time.perf_counter() - t0)
    setup, step, moved = [], [], []
    poses = [_Pose(p) for p in placed]
    before_last = CandidateEnergy(problem, poses[:-1], pending=[poses[-1].id])
    for _ in range(5):
        t0 = time.perf_counter()
        CandidateEnergy(problem, poses)
        setup.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        before_last.after(poses[-1])  # what a placer's step does: the 15th object added to the 14 before it
        step.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        energy.without(poses[0].id)  # what a repair does to score other poses for a placed object
        moved.append(time.perf_counter() - t0)
    sample = np.random.default_rng(0).choice(len(cands), size=min(200, len(cands)), replace=False)
    t0 = time.perf_counter()
    exact_nav = energy.score(obj, cands[sample], nav_mode="exact")
    exact_nav_each = (time.perf_counter() - t0) / len(sample)
    fast = energy.score(obj, cands[sample])
    agree = float(np.mean(np.abs(fast["nav"] - exact_nav["nav"]) < 1e-9))
    t0 = time.perf_counter()
    for i in sample:
        x, z, r = cands[i]
        layout_energy(plan, placed + [Placement(id=obj.id, type=obj.type, x=x, z=z, rotation=r, size=obj.size)],
                      problem)
    exact_each = (time.perf_counter() - t0) / len(sample)
    vec = statistics.median(runs)
    print(f"energy of every candidate of object 16 in a 5 m x 5 m room with {len(placed)} placed objects")
    print(f"  candidates (0.1 m grid x 4 rotations)   {len(cands)}")
    print(f"  vectorised: all candidates             {1000 * vec:8.2f} ms  (median of 20)")
    print(f"  set-up for the placed objects          {1000 * statistics.median(setup):8.2f} ms  from scratch (baseline, median of 5)")
    print(f"                                         {1000 * statistics.median(step):8.2f} ms  incremental, one object added "
          f"(after; {statistics.median(setup) / statistics.median(step):.0f}x less)")
    print(f"                                         {1000 * statistics.median(moved):8.2f} ms  incremental, one object taken "
          f"out (without; {statistics.median(setup) / statistics.median(moved):.0f}x less)")
    print(f"  exact: per candidate                   {1000 * exact_each:8.2f} ms  (measured on {len(sample)})")
    print(f"  exact: all candidates (projected)      {exact_each * len(cands):8.2f} s")
    print(f"  ratio exact / vectorised               {exact_each * len(cands) / vec:8.0f}x")
    print(f"  vectorised with exact navigation       {1000 * exact_nav_each:8.3f} ms per candidate "
          f"(for re-ranking a placer's best few)")
    print(f"  fast navigation agrees with exact on   {100 * agree:8.1f} % of the {len(sample)} candidates")
    return 0
