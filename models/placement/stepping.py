"""Placement as an iterator of steps: `for step in Stepping(solver, plan, seed): ...` (or `async for`) hands over
each `PlacementStep` as the placer makes it (the solver runs in a worker thread and reports through its observer),
and `layout` holds the result once the iteration is over. Any solver works; Plan2Place's steps carry the
policy's probability of every candidate (the floor heat-map), the repairs' steps their reason."""

from __future__ import annotations

import asyncio
import queue
import threading
from collections.abc import AsyncIterator, Callable, Iterator

import numpy as np

from models.placement.base import Fixed, PlacementStep, Solver
from models.values import ConstraintPlan, Layout

TOP = 5  # candidates listed per step in a step's record, unless asked for more
_DONE = object()


class Stepping:
    def __init__(self, solver: Solver, plan: ConstraintPlan, seed: int = 0, fixed: Fixed | None = None):
        self.solver, self.plan, self.seed, self.fixed = solver, plan, seed, fixed
        self.layout: Layout | None = None

    def __iter__(self) -> Iterator[PlacementStep]:
        """The steps in order; the solver's error, if any, is raised after the steps made before it. Leaving
        the loop early does not stop the solver: it finishes in its thread and `layout` is set then."""
        steps: queue.Queue = queue.Queue()
        failure = self._start(steps.put)
        while (step := steps.get()) is not _DONE:
            yield step
        if failure:
            raise failure[0]

    async def __aiter__(self) -> AsyncIterator[PlacementStep]:
        """The same for an event loop (an HTTP server streaming the steps): each step is handed to the loop as it
        is made, with no thread hop per step on the reading side."""
        loop, steps = asyncio.get_running_loop(), asyncio.Queue()
        failure = self._start(lambda step: loop.call_soon_threadsafe(steps.put_nowait, step))
        while (step := await steps.get()) is not _DONE:
            yield step
        if failure:
            raise failure[0]

    def _start(self, put: Callable[[object], None]) -> list[BaseException]:
        """Run the solver in a worker thread, `put`ting each step and then `_DONE`; the list it returns holds the
        solver's error, if any, once `_DONE` is put."""
        failure: list[BaseException] = []

        def run() -> None:
            try:
                self.layout = self.solver.solve(self.plan, seed=self.seed, observer=put, fixed=self.fixed)
            except BaseException as e:  # handed to the iterating side
                failure.append(e)
            finally:
                put(_DONE)

        threading.Thread(target=run, daemon=True, name=f"stepping-{self.plan.id}").start()
        return failure


def step_record(step: PlacementStep, index: int, top: int = TOP) -> dict:
    """One step as JSON-ready data: the pose (None when the object was left out), the energy terms after it,
    why a repair moved it (or the reach guard chose it), whether the room is solved again from empty at this step
    (`restart`, models.placement.reorder), how many candidates were legal, and the `top` best-scored ones (x, z,
    rotation, score; Plan2Place's scores are the policy's probabilities: all of them make the floor heat-map)."""
    scores = np.asarray(step.scores, dtype=float)
    legal = np.flatnonzero(np.isfinite(scores))
    best = legal[np.argsort(-scores[legal], kind="stable")[:top]]  # ties in candidate order
    return {"step": index, "object": step.object_id, "x": step.x, "z": step.z, "rotation": step.rotation,
            "why": step.why, "restart": step.restart, "terms": {k: round(v, 6) for k, v in step.terms.items()},
            "candidates": len(scores), "legal": len(legal),
            "top": np.column_stack([np.round(np.asarray(step.candidates, dtype=float)[best], 4),
                                    np.round(scores[best], 6)]).tolist()}
