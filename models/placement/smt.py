"""Z3 placer: the same model stated as logic and handed to Z3's Optimize with a time limit.

Positions are reals, rotations and `placed` flags 0/1 integers; each condition is an implication, each
disjunction an `Or`, each soft constraint an `add_soft` with its weight, so Z3 searches the
disjunctions itself instead of through big-M rows. The seed sets Z3's random seeds.
"""

from __future__ import annotations

import threading
import time

import z3

from models.placement.formulation import Expr, Model, ModelSolver, ObjVars


READ_MARGIN_S = 0.05


class Z3Solver(ModelSolver):
    name = "z3"
    no_solution = "Z3 found no model within the time budget"

    def __init__(self, time_budget_s: float | None = None):
        super().__init__(time_budget_s)

    def run(self, model: Model, ov: dict[str, ObjVars], seed: int, seconds: float):
        # a context of its own: Z3's shared one keeps state from the solves before, so the same model and seed gave
        # another layout after another solve in the same process
        z3.set_param("smt.random_seed", int(seed) % 2**31, "sat.random_seed", int(seed) % 2**31)
        ctx = z3.Context()
        v = {n: (z3.Int(n, ctx) if var.binary else z3.Real(n, ctx)) for n, var in model.vars.items()}

        def lin(e: Expr):
            return z3.Sum([z3.RealVal(0, ctx)] + [c * v[n] for n, c in e.terms.items()]) + e.const

        def on(names: list[str]):
            return z3.And([v[n] == 1 for n in names]) if names else z3.BoolVal(True, ctx)

        def statements():
            """Add the model to `opt`, one statement per step."""
            for n, var in model.vars.items():
                yield opt.add(v[n] >= var.lo, v[n] <= var.hi)
            for when, rows in model.hard:
                yield opt.add(z3.Implies(on(when), z3.And([lin(r) <= 0 for r in rows])))
            for when, groups, _ in model.choices:
                yield opt.add(z3.Implies(on(when), z3.Or([z3.And([lin(r) <= 0 for r in g]) for g in groups])))
            # the objective's binary terms (soft constraints, placed flags) become weighted soft goals
            for n, coef in model.objective.terms.items():
                if model.vars[n].binary and coef < 0:
                    yield opt.add_soft(v[n] == 1, weight=str(round(-coef, 4)))

        deadline = time.perf_counter() + seconds
        opt = z3.Optimize(ctx=ctx)
        # stating a big model through the Python API can outlast the budget on its own: stop when it does
        for _ in statements():
            if time.perf_counter() > deadline - READ_MARGIN_S:
                return {}, {oid: f"Z3 could not state the model within {seconds:.2f} s" for oid in ov}
        # stating the model takes time too: Z3 gets what is left, less a margin for reading the model back
        left = max(0.02, deadline - time.perf_counter() - READ_MARGIN_S)
        opt.set("timeout", int(1000 * left))
        # Optimize does not always honour its timeout (an 11 s run on a 2.3 s budget was measured):
        # interrupt it from a timer as well
        stop = threading.Timer(left, opt.ctx.interrupt)
        stop.start()
        try:
            result = opt.check()
        except z3.Z3Exception as e:  # the timer's interrupt can reach check() as an exception ("canceled")
            result = _message(e)
        finally:
            stop.cancel()
        poses, reasons = {}, {}
        try:
            m = opt.model()
        except z3.Z3Exception:
            m = None

        def val(name: str) -> float:
            x = m.eval(v[name], model_completion=True)
            return float(x.as_fraction()) if z3.is_rational_value(x) else float(x.as_long())

        if m is not None:
            try:
                for oid, o in ov.items():
                    if val(o.placed) > 0.5:
                        k = max(range(4), key=lambda i: val(o.rot[i]))
                        poses[oid] = (val(f"x[{oid}]"), val(f"z[{oid}]"), 90.0 * k)
                    else:
                        reasons[oid] = "Z3's best model leaves it out: no position fits with the others"
            except z3.Z3Exception as e:  # the timer fired as check() returned: reading the model is canceled too
                poses, m, result = {}, None, _message(e)
        if m is None:
            reasons = {oid: f"Z3 found no model in {seconds:.2f} s ({result})" for oid in ov}
        return poses, reasons


def _message(e) -> str:
    """A Z3Exception's message ("canceled" when the budget's timer interrupted Z3)."""
    return e.value.decode() if isinstance(e.value, bytes) else str(e.value)
