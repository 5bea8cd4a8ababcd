"""Two exact shortcuts against the code before them: the polish's count of constraints met reading each relation's
result for every pose of an object from a cache kept per pose of the other object (`CandidateScorer.relation_met`),
and the restarts sharing the first solve's plan-only parts (`_solved(..., shares=)`). Per-object solve time of
Plan2Place, the two variants alternating per run in one process, and whether the layouts are identical. Run from a
tree's root: PYTHONPATH=. python app/bench/results/plan2place/speed/relation-cache.py dense 20 2"""
import sys
import time

import numpy as np

from app.bench.placement import pick_records
from models.constraints.evaluate import Poses, relation_met
from models.placement import greedy, polish
from models.placement.base import get_solver
from models.placement.candidates import poses_of


def met_before(ep, oid, idx, others):
    """`polish.met` as it was: each relation computed for the poses asked, every time."""
    obj = ep.problem.plan.object(oid)
    cands, body = ep.scorer.bodies(obj)
    if idx is not None:
        cands, body = cands[idx], body[idx]
    poses = poses_of(cands, obj, body)
    objects = ep.problem.constraints.objects
    count = np.zeros(len(cands), int)
    if oid in objects:
        oc = objects[oid]
        ok = ep.scorer.placement_met(obj, oc.placement)
        count += ok if idx is None else ok[idx]
        by_id = {p.id: p for p in others}
        for c in oc.relations:
            if c.target in by_id:
                count += relation_met(c.name, poses, Poses.one(*polish._shape(by_id[c.target])))
    for p in others:
        for c in objects[p.id].relations if p.id in objects else ():
            if c.target == oid:
                count += relation_met(c.name, Poses.one(*polish._shape(p)), poses)
    return count


def main(dataset: str, n: int, seeds: int) -> None:
    plans = [r.plan for r in pick_records(dataset, n)]
    solver = get_solver("plan2place")
    solver.solve(plans[0], seed=0)
    met_now, solved_now = polish.met, greedy._solved

    def solved_before(*args, shares=None):
        return solved_now(*args[:7])  # no shares: each restart makes its plan-only parts again

    variants = {"old": (met_before, solved_before), "new": (met_now, solved_now)}
    times = {v: [] for v in variants}
    same = runs = 0
    for seed in range(seeds):
        for i, plan in enumerate(plans):
            out = {}
            for v in (("old", "new") if (i + seed) % 2 == 0 else ("new", "old")):
                polish.met, greedy._solved = variants[v]
                for module in ("groups", "habits"):  # they import `met` by name
                    setattr(sys.modules[f"models.placement.{module}"], "met", variants[v][0])
                t = time.perf_counter()
                layout = solver.solve(plan, seed=seed)
                times[v].append(1000 * (time.perf_counter() - t) / len(plan.objects))
                out[v] = layout.model_dump(exclude={"timing"})
            runs += 1
            same += out["old"] == out["new"]
    print(dataset, "runs", runs, "identical", same)
    for v, t in times.items():
        print(v, "p50 %.2f mean %.2f" % (np.median(t), np.mean(t)))
    print("ratio p50 new/old %.3f mean %.3f" % (np.median(times["new"]) / np.median(times["old"]),
                                               np.mean(times["new"]) / np.mean(times["old"])))


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
