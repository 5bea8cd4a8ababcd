"""MILP placer (Holodeck's formulation) solved with HiGHS.

Every condition of the shared model becomes rows with a big-M computed from the variables' bounds;
every disjunction gets one binary per alternative. HiGHS runs with the seed and a time limit and the
best incumbent is read back; objects whose `placed` binary is 0 are reported unplaced.
"""

from __future__ import annotations

import highspy
import numpy as np

from models.placement.formulation import Expr, Model, ModelSolver, ObjVars

INF = highspy.kHighsInf


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

    def __init__(self, time_budget_s: float = 3.0):
        super().__init__(time_budget_s)

    def run(self, model: Model, ov: dict[str, ObjVars], seed: int, seconds: float):
        names = list(model.vars)
        index = {n: i for i, n in enumerate(names)}
        rows = big_m_rows(model, index)
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
        values = list(h.getSolution().col_value) if h.getInfo().primal_solution_status >= 1 else []
        poses, reasons = {}, {}
        if values:
            for oid, v in ov.items():
                if values[index[v.placed]] > 0.5:
                    k = int(np.argmax([values[index[r]] for r in v.rot]))
                    poses[oid] = (values[index[f"x[{oid}]"]], values[index[f"z[{oid}]"]], 90.0 * k)
                else:
                    reasons[oid] = "the MILP solution leaves it out: no position fits with the others"
        return poses, reasons
