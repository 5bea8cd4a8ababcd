"""MILP placer (Holodeck's formulation) solved with HiGHS.

Every condition of the shared model becomes rows with a big-M computed from the variables' bounds;
every disjunction gets one binary per alternative. HiGHS runs with the seed and a time limit and the
best feasible incumbent (primal solution status 2; 1 means infeasible) is read back; objects whose
`placed` binary is 0 are reported unplaced.

Two ways to run it (issue 7: measured in the README's placement section):
- `incremental` (the default): object by object in the problem's order, the way Holodeck grows a
  layout, each a small MILP with the objects placed so far pinned, each with an equal share of the
  budget. One object that does not fit is reported and the rest go on.
- `whole`: one monolithic model for all objects; on large rooms it often finds no incumbent at all.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from functools import cache

import highspy
import numpy as np

from models.placement.formulation import Expr, Model, ModelSolver, ObjVars, build
from models.placement.problem import PlacementProblem, time_budget
from models.placement.result import make_layout
from models.values import ConstraintPlan, Layout

FEASIBLE = 2  # HiGHS primal_solution_status: 0 none, 1 infeasible, 2 feasible

INF = highspy.kHighsInf
_REDIRECT = threading.Lock()  # one redirection of the process's stdout at a time (`_first_model_quietly`)


@cache
def _first_model_quietly() -> None:
    """HiGHS prints its banner on the C-level stdout when a process makes its first model, before any option
    can be set. That first model is made here with stdout pointed at stderr, so that stdout carries only what
    the CLI promises (`h3ds place --steps -` writes JSON lines there)."""
    with _REDIRECT:
        sys.stdout.flush()
        saved = os.dup(1)
        try:
            os.dup2(2, 1)
            highspy.Highs()
        finally:
            os.dup2(saved, 1)
            os.close(saved)


class _Rows:
    def __init__(self, index: dict[str, int]):
        self.index = index
        self.lower: list[float] = []
        self.upper: list[float] = []
        self.starts: list[int] = []
        self.cols: list[int] = []
        self.vals: list[float] = []

    def add(self, e: Expr, upper: float) -> None:
        """e.terms . vars <= upper - e.const"""
        self.starts.append(len(self.cols))
        for name, coef in e.terms.items():
            if coef != 0:
                self.cols.append(self.index[name])
                self.vals.append(coef)
        self.lower.append(-INF)
        self.upper.append(upper - e.const)


def big_m_rows(m: Model, index: dict[str, int]) -> _Rows:
    rows = _Rows(index)

    def guarded(when: list[str], row: Expr) -> None:
        if not when:
            rows.add(row, 0.0)
            return
        big = max(m.bound(row), 0.0)
        # row <= big * (len(when) - sum(when))
        rows.add(row + sum((Expr({w: big}) for w in when), Expr()), big * len(when))

    for when, rs in m.hard:
        for r in rs:
            guarded(when, r)
    for when, groups, names in m.choices:
        # sum(choice binaries) >= 1 when all `when` are 1
        rows.add(sum((Expr({w: 1.0}) for w in when), Expr()) - sum((Expr({n: 1.0}) for n in names), Expr()),
                 len(when) - 1)
        for name, group in zip(names, groups):
            for r in group:
                guarded([name], r)
    return rows


class MILPSolver(ModelSolver):
    name = "milp"
    no_solution = "HiGHS found no feasible layout within the time budget"

    def __init__(self, time_budget_s: float | None = None, mode: str = "incremental"):
        super().__init__(time_budget_s)
        if mode not in ("incremental", "whole"):
            raise ValueError(f"unknown MILP mode {mode!r}; use 'incremental' or 'whole'")
        self.mode = mode

    def solve(self, plan: ConstraintPlan, seed: int = 0, time_budget_s: float | None = None,
              observer=None, fixed: dict[str, tuple[float, float, float]] | None = None) -> Layout:
        if self.mode == "whole":
            return super().solve(plan, seed, time_budget_s, observer, fixed)
        start = time.perf_counter()
        budget = time_budget(plan, time_budget_s if time_budget_s is not None else self.time_budget_s)
        full = PlacementProblem.from_plan(plan, fixed)
        poses = dict(full.fixed)
        pins = dict(full.fixed)  # each object pinned where it was first put, so it cannot drift step by step
        reasons: dict[str, str] = {}
        todo = [o for o in full.order if o.id not in poses]
        for i, obj in enumerate(todo):
            left = budget - (time.perf_counter() - start)
            if left <= 0:
                reasons.update({o.id: "time budget ran out before it was placed" for o in todo[i:]})
                break
            placed_ids = set(poses) | {obj.id}
            sub = plan.model_copy(update={"objects": [o for o in plan.objects if o.id in placed_ids]})
            problem = PlacementProblem.from_plan(sub, pins)
            model, ov = build(problem, seed)
            got, why = self.run(model, ov, seed, max(0.05, left / (len(todo) - i)))
            if obj.id in got:
                poses.update(got)  # pinned objects may move by the pin tolerance: keep one consistent solution
                pins[obj.id] = got[obj.id]
            else:
                reasons[obj.id] = why.get(obj.id, self.no_solution)
            if observer is not None:
                x, z, r = poses.get(obj.id, (None, None, None))
                from models.placement.base import PlacementStep
                observer(PlacementStep(obj.id, x, z, r, np.empty((0, 3)), np.empty(0), {}))
        return make_layout(full, poses, reasons, self.name, seed, time.perf_counter() - start,
                           default_reason=self.no_solution)

    def run(self, model: Model, ov: dict[str, ObjVars], seed: int, seconds: float):
        names = list(model.vars)
        index = {n: i for i, n in enumerate(names)}
        rows = big_m_rows(model, index)
        _first_model_quietly()
        h = highspy.Highs()
        h.setOptionValue("output_flag", False)
        h.setOptionValue("random_seed", int(seed) % 2_147_483_647)
        h.setOptionValue("threads", 1)
        h.setOptionValue("time_limit", seconds)
        lo = np.array([model.vars[n].lo for n in names])
        hi = np.array([model.vars[n].hi for n in names])
        cost = np.array([model.objective.terms.get(n, 0.0) for n in names])
        h.addVars(len(names), lo, hi)
        h.changeColsCost(len(names), np.arange(len(names), dtype=np.int32), cost)
        ints = np.array([i for i, n in enumerate(names) if model.vars[n].binary], dtype=np.int32)
        h.changeColsIntegrality(len(ints), ints, np.full(len(ints), highspy.HighsVarType.kInteger))
        if rows.lower:
            h.addRows(len(rows.lower), np.array(rows.lower), np.array(rows.upper), len(rows.cols),
                      np.array(rows.starts, dtype=np.int32), np.array(rows.cols, dtype=np.int32),
                      np.array(rows.vals))
        h.run()
        feasible = h.getInfo().primal_solution_status == FEASIBLE
        values = list(h.getSolution().col_value) if feasible else []
        poses, reasons = {}, {}
        if not feasible:
            status = h.modelStatusToString(h.getModelStatus())
            reasons = {oid: f"HiGHS found no feasible layout in {seconds:.2f} s ({status})" for oid in ov}
        if values:
            for oid, v in ov.items():
                if values[index[v.placed]] > 0.5:
                    k = int(np.argmax([values[index[r]] for r in v.rot]))
                    poses[oid] = (values[index[f"x[{oid}]"]], values[index[f"z[{oid}]"]], 90.0 * k)
                else:
                    reasons[oid] = "the MILP solution leaves it out: no position fits with the others"
        return poses, reasons
