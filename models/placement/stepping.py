"""Placement as an iterator of steps: `for step in Stepping(solver, plan, seed): ...` hands over each
`PlacementStep` as the placer makes it (the solver runs in a worker thread and reports through its observer),
and `layout` holds the result once the iteration is over. Any solver works; Plan2Place's steps carry the
policy's probability of every candidate (the floor heat-map), the repairs' steps their reason."""

from __future__ import annotations

import math
import queue
import threading
from collections.abc import Iterator

from models.placement.base import Fixed, PlacementStep, Solver
from models.values import ConstraintPlan, Layout

TOP = 5  # candidates listed per step in a step's record
_DONE = object()


class Stepping:
    def __init__(self, solver: Solver, plan: ConstraintPlan, seed: int = 0, fixed: Fixed | None = None):
        self.solver, self.plan, self.seed, self.fixed = solver, plan, seed, fixed
        self.layout: Layout | None = None

    def __iter__(self) -> Iterator[PlacementStep]:
        """The steps in order; the solver's error, if any, is raised after the steps made before it. Leaving
        the loop early does not stop the solver: it finishes in its thread and `layout` is set then."""
        steps: queue.Queue = queue.Queue()
        failure: list[BaseException] = []

        def run() -> None:
            try:
                self.layout = self.solver.solve(self.plan, seed=self.seed, observer=steps.put, fixed=self.fixed)
            except BaseException as e:  # handed to the iterating thread
                failure.append(e)
            finally:
                steps.put(_DONE)

        worker = threading.Thread(target=run, daemon=True, name=f"stepping-{self.plan.id}")
        worker.start()
        while (step := steps.get()) is not _DONE:
            yield step
        worker.join()
        if failure:
            raise failure[0]


def step_record(step: PlacementStep, index: int) -> dict:
    """One step as JSON-ready data: the pose (None when the object was left out), the energy terms after it,
    why a repair moved it (or the reach guard chose it), whether the room is solved again from empty at this step
    (`restart`, models.placement.reorder), how many candidates were legal, and the `TOP`
    best-scored ones (x, z, rotation, score; Plan2Place's scores are the policy's probabilities)."""
    legal = [i for i, s in enumerate(step.scores) if math.isfinite(s)]
    best = sorted(legal, key=lambda i: -step.scores[i])[:TOP]
    return {"step": index, "object": step.object_id, "x": step.x, "z": step.z, "rotation": step.rotation,
            "why": step.why, "restart": step.restart, "terms": {k: round(v, 6) for k, v in step.terms.items()},
            "candidates": len(step.scores), "legal": len(legal),
            "top": [[*(round(float(v), 4) for v in step.candidates[i]), round(float(step.scores[i]), 6)]
                    for i in best]}
