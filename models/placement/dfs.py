"""A depth-first placer in the manner of Holodeck's DFS solver.

Objects are taken in dependency order; for each, every grid pose in four rotations is filtered by the
hard rules and scored by its constraints, and the search branches over the best few. It stops at the
first layout that places everything, or when the time budget runs out, returning the best layout seen
(most objects placed, then highest score). Unlike Holodeck's, it never drops an object silently: an
object with no valid pose is reported in `unplaced` with the reason.
"""

from __future__ import annotations

import time

import numpy as np

from models.placement import blas
from models.placement.base import Fixed, PlacementStep, StepObserver
from models.placement.candidates import CandidateScorer, PlacedObject
from models.placement.problem import PlacementProblem, time_budget
from models.placement.result import NO_ROOM, make_layout
from models.values import ConstraintPlan, Layout

BRANCH = 3
MIN_SPREAD = 0.3  # branches differ by at least this much (m), or by rotation


class DFSSolver:
    name = "dfs"

    def __init__(self, branch: int = BRANCH, time_budget_s: float | None = None):
        self.branch = branch
        self.time_budget_s = time_budget_s  # None: the shared per-object rule (problem.time_budget)

    def solve(self, plan: ConstraintPlan, seed: int = 0, time_budget_s: float | None = None,
              observer: StepObserver | None = None, fixed: Fixed | None = None) -> Layout:
        with blas.one_blas_thread():  # as the step-wise placers (models.placement.blas)
            return self._search(plan, seed, time_budget_s, observer, fixed)

    def _search(self, plan: ConstraintPlan, seed: int, time_budget_s: float | None, observer: StepObserver | None,
                fixed: Fixed | None) -> Layout:
        start = time.perf_counter()
        deadline = start + time_budget(plan, time_budget_s if time_budget_s is not None else self.time_budget_s)
        problem = PlacementProblem.from_plan(plan, fixed)
        scorer = CandidateScorer(problem)
        rng = np.random.default_rng(seed)
        order = problem.order
        best: dict = {"placed": [], "failed": {}, "key": (-1, -np.inf), "steps": []}

        def choices(i: int, placed: list[PlacedObject]):
            obj = order[i]
            if obj.id in problem.fixed:  # a kept pose is the only choice
                return np.array([problem.fixed[obj.id]], float), np.zeros(1), {}, [0]
            cands, scores, terms = scorer.evaluate(obj, placed, strict=True)
            if not np.isfinite(scores).any():  # relax the front-clearance rules before giving up
                cands, scores, terms = scorer.evaluate(obj, placed, strict=False)
            scores = scores + rng.uniform(0, 1e-3, size=len(scores))
            picks: list[int] = []
            for idx in np.argsort(-scores):
                if not np.isfinite(scores[idx]) or len(picks) == self.branch:
                    break
                if all(cands[idx, 2] != cands[j, 2] or np.hypot(*(cands[idx, :2] - cands[j, :2])) >= MIN_SPREAD
                       for j in picks):
                    picks.append(int(idx))
            return cands, scores, terms, picks

        def search(i: int, placed: list[PlacedObject], failed: dict[str, str], total: float, steps: list) -> bool:
            if i == len(order) or time.perf_counter() > deadline:
                key = (len(placed), total)
                if key > best["key"]:
                    best.update(placed=list(placed), failed=dict(failed), key=key, steps=list(steps))
                return i == len(order) and not failed
            obj = order[i]
            cands, scores, terms, picks = choices(i, placed)
            if not picks:
                steps.append(PlacementStep(obj.id, None, None, None, cands, scores, {}))
                found = search(i + 1, placed, {**failed, obj.id: NO_ROOM}, total, steps)
                steps.pop()
                return found
            for idx in picks:
                x, z, rot = (float(v) for v in cands[idx])
                placed.append(scorer.place(obj, x, z, rot))
                steps.append(PlacementStep(obj.id, x, z, rot, cands, scores,
                                           {k: float(v[idx]) for k, v in terms.items()}))
                if search(i + 1, placed, failed, total + float(scores[idx]), steps):
                    return True
                placed.pop()
                steps.pop()
                if time.perf_counter() > deadline:
                    break
            return False

        search(0, [], {}, 0.0, [])
        if observer is not None:
            for step in best["steps"]:
                observer(step)
        poses = {p.id: (p.x, p.z, p.rotation) for p in best["placed"]}
        return make_layout(problem, poses, best["failed"], self.name, seed, time.perf_counter() - start,
                           default_reason="time budget ran out before it was placed")
