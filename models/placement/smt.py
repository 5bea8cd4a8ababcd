"""Z3 placer: the same model written as SMT-LIB text and handed to Z3's Optimize with a time limit (or, for the
exact finish, a budget of Z3's own work, which ends at the same point on any machine).

Positions are reals, rotations and `placed` flags 0/1 integers; each condition is an implication, each
disjunction an `or`, each soft constraint an `assert-soft` with its weight, so Z3 searches the
disjunctions itself instead of through big-M rows. The seed sets Z3's random seeds.
"""

from __future__ import annotations

import threading
import time
from decimal import Decimal

import z3

from models.placement.formulation import PIN, Expr, Model, ModelSolver, ObjVars, build, pins
from models.placement.problem import PlacementProblem
from models.values import ConstraintPlan

READ_MARGIN_S = 0.05
DECIDED = 2 * PIN  # a row between kept poses holds when at most this over (their poses' rounding)
Pose = tuple[float, float, float]


class Z3Solver(ModelSolver):
    name = "z3"
    no_solution = "Z3 found no model within the time budget"

    def __init__(self, time_budget_s: float | None = None, work_per_object: int | None = None):
        """`work_per_object`: a budget in Z3's own resource count (its `rlimit`) per object, so that a seed gets the
        same layout on any machine; the time budget then only guards against a stall."""
        super().__init__(time_budget_s)
        self.work_per_object = work_per_object

    def run(self, model: Model, ov: dict[str, ObjVars], seed: int, seconds: float):
        deadline = time.perf_counter() + seconds
        ctx = _context(seed)
        text, names = smtlib(model)
        opt = z3.Optimize(ctx=ctx)
        opt.from_string(text)
        # Z3 gets what is left of the budget, less a margin for reading the model back
        left = max(0.02, deadline - time.perf_counter() - READ_MARGIN_S)
        opt.set("timeout", int(1000 * left))
        if self.work_per_object:
            opt.set("rlimit", self.work_per_object * len(ov))
        # Optimize does not always honour its timeout (an 11 s run on a 2.3 s budget was measured):
        # interrupt it from a timer as well
        stop = threading.Timer(left, opt.ctx.interrupt)
        stop.start()
        try:
            result = opt.check()
            result = result if result != z3.unknown else opt.reason_unknown()
        except z3.Z3Exception as e:  # the timer's interrupt can reach check() as an exception ("canceled")
            result = _message(e)
        finally:
            stop.cancel()
        poses = {}
        try:
            m = opt.model()
        except z3.Z3Exception:
            m = None
        if m is not None:
            try:
                poses = _poses(m, model, names, ov)
            except z3.Z3Exception as e:  # the timer fired as check() returned: reading the model is canceled too
                poses, m, result = {}, None, _message(e)
        if m is None:
            return poses, {oid: f"Z3 found no model within {self._budget(seconds, ov)} ({result})" for oid in ov}
        why = ("Z3's best model leaves it out: no position fits with the others" if str(result) == "sat" else
               f"Z3's best model when its budget ({self._budget(seconds, ov)}) ran out leaves it out")
        return poses, {oid: why for oid in ov if oid not in poses}

    def _budget(self, seconds: float, ov: dict) -> str:
        work = f" or {self.work_per_object * len(ov):,} units of its work" if self.work_per_object else ""
        return f"{seconds:.2f} s{work}"


def met_goals(plan: ConstraintPlan, poses: dict[str, Pose]) -> set[str]:
    """The model's soft goals (constraints, clearances) that the layout `poses` meets: every object pinned, Z3's
    optimiser sets each goal that can hold."""
    problem = PlacementProblem.from_plan(plan, poses)
    model, ov = build(problem, round_gaps=True)
    model = model.pinned(pins(problem, ov), DECIDED)
    text, names = smtlib(model)
    ctx = z3.Context()
    opt = z3.Optimize(ctx=ctx)
    opt.from_string(text)
    if opt.check() != z3.sat:
        return set()
    m = opt.model()
    return {g for g in model.goals if m.eval(z3.Int(names[g], ctx), model_completion=True).as_long() == 1}


def one_more_met(plan: ConstraintPlan, kept: dict[str, Pose], met: set[str], seed: int, work: int,
                 seconds: float) -> dict[str, Pose] | None:
    """A layout of every object with the poses `kept` in which every soft goal of `met` holds and at least one more
    of the plan's constraints: any such layout (Z3's solver, not its optimiser), or None where Z3 finds none within
    `work` units of its resource count (or `seconds`)."""
    problem = PlacementProblem.from_plan(plan, kept)
    model, ov = build(problem, seed, round_gaps=True)
    model = model.pinned(pins(problem, ov), DECIDED)
    text, names = smtlib(model, goals=False)
    ctx = _context(seed)
    solver = z3.Solver(ctx=ctx)
    solver.from_string(text)

    def holds(binary: str):
        return z3.Int(names[binary], ctx) == 1

    more = [holds(g) for g, constraint in model.goals.items() if constraint and g not in met]
    if not more:  # the model meets every constraint where the judge finds one broken (a gap at a threshold)
        return None
    solver.add(*(holds(o.placed) for o in ov.values()), *(holds(g) for g in met), z3.Or(more))
    solver.set("rlimit", work, "timeout", max(1, int(1000 * seconds)))
    return _poses(solver.model(), model, names, ov) if solver.check() == z3.sat else None


def _context(seed: int) -> z3.Context:
    """A Z3 context of its own, seeded: Z3's shared one keeps state from the solves before, so the same model and seed
    gave another layout after another solve in the same process."""
    z3.set_param("smt.random_seed", int(seed) % 2**31, "sat.random_seed", int(seed) % 2**31)
    return z3.Context()


def _poses(m, model: Model, names: dict[str, str], ov: dict[str, ObjVars]) -> dict[str, Pose]:
    """The placed objects' poses in Z3's model `m` of `model` (`names`: its variables' names in the text)."""
    def val(name: str) -> float:
        const = (z3.Int if model.vars[name].binary else z3.Real)(names[name], m.ctx)  # the parsed variable
        x = m.eval(const, model_completion=True)
        return float(x.as_fraction()) if z3.is_rational_value(x) else float(x.as_long())

    poses = {}
    for oid, o in ov.items():
        if val(o.placed) > 0.5:
            k = max(range(4), key=lambda i: val(o.rot[i]))
            poses[oid] = (val(f"x[{oid}]"), val(f"z[{oid}]"), 90.0 * k)
    return poses


def smtlib(model: Model, goals: bool = True) -> tuple[str, dict[str, str]]:
    """`model` as SMT-LIB 2 text for Z3's parser, and its variables' names there (v0, v1, ...). Stating a model
    through Z3's Python API took longer than solving it (0.4-0.7 s against 0.2-0.4 s for a room of 7-9 objects);
    the parser states it in C++. Each condition is an implication, each disjunction an `or`, and the objective's
    binary terms (soft constraints, placed flags) weighted soft goals (without `goals`: none, a question of
    satisfiability)."""
    names = {n: f"v{k}" for k, n in enumerate(model.vars)}

    def num(c: float) -> str:
        d = format(Decimal(repr(float(c))), "f")
        return f"(- {d[1:]})" if d.startswith("-") else d

    def term(n: str) -> str:
        return f"(to_real {names[n]})" if model.vars[n].binary else names[n]

    def row(e: Expr) -> str:
        parts = [f"(* {num(c)} {term(n)})" for n, c in e.terms.items()] + [num(e.const)]
        return f"(<= (+ {' '.join(parts)}) 0.0)"

    def every(rows: list[str]) -> str:
        return f"(and {' '.join(rows)})" if rows else "true"

    def on(when: list[str]) -> str:
        return every([f"(= {names[n]} 1)" for n in when])

    lines = [f"(declare-const {names[n]} {'Int' if var.binary else 'Real'})" for n, var in model.vars.items()]
    for n, var in model.vars.items():
        lo, hi = (str(round(var.lo)), str(round(var.hi))) if var.binary else (num(var.lo), num(var.hi))
        lines.append(f"(assert (and (>= {names[n]} {lo}) (<= {names[n]} {hi})))")
    lines += [f"(assert (=> {on(when)} {every([row(r) for r in rows])}))" for when, rows in model.hard]
    lines += [f"(assert (=> {on(when)} (or {' '.join(every([row(r) for r in g]) for g in groups) or 'false'})))"
              for when, groups, _ in model.choices]
    lines += [f"(assert-soft (= {names[n]} 1) :weight {num(round(-c, 4))})"
              for n, c in model.objective.terms.items() if goals and model.vars[n].binary and c < 0]
    return "\n".join(lines), names


def _message(e) -> str:
    """A Z3Exception's message ("canceled" when the budget's timer interrupted Z3)."""
    return e.value.decode() if isinstance(e.value, bytes) else str(e.value)
