"""The placement problem as a mixed-integer model that two solvers read in their own way.

One description, two readings: the MILP backend (HiGHS) turns every condition into big-M rows, as
Holodeck's MILP solver does; the Z3 backend states the same conditions as logic (implications and
disjunctions), as SMT-based layout solvers do. The model itself is Holodeck's formulation:

- per object: centre (x, z), four rotation binaries, and a `placed` binary (an object that cannot fit
  is left out at a large cost, so the solvers report it unplaced instead of failing);
- hard: inside the room, no overlap (a 4-way disjunction per pair), door clearance kept free;
- soft, each with a satisfied-binary and a weight: edge / middle, every relation of constraints.md
  (linearised per rotation of the target), and front clearance of functional objects.
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass, field

import numpy as np

from models.constraints.evaluate import (ALIGN_TOL, AROUND_MAX_GAP, EDGE_TOL, FAR_MIN, FRONT_MAX_GAP, LATERAL_SLACK,
                                         MIDDLE_MIN, NEAR_MAX, SIDE_MAX_GAP)
from models.placement.base import PlacementStep
from models.placement.problem import DOOR_CLEARANCE, PlacementProblem, time_budget
from models.placement.result import make_layout
from models.values import ConstraintPlan, Layout, PlanObject

UNPLACED_COST = {True: 1000.0, False: 100.0}  # task object? -> cost of leaving it out
GLOBAL_WEIGHT = 2.0
RELATION_WEIGHT = 1.0
CLEARANCE_WEIGHT = 1.0
NEAR_LINF = 0.7  # box-to-box distance along each axis; within it, the gap is at most ~1 m
AROUND_LINF = 0.42
PIN = 0.005  # a kept pose may move this much, so that poses rounded to 0.1 mm stay feasible


@dataclass
class Expr:
    """A linear expression: sum(coef * var) + const."""

    terms: dict[str, float] = field(default_factory=dict)
    const: float = 0.0

    def __add__(self, other) -> Expr:
        other = other if isinstance(other, Expr) else Expr(const=float(other))
        terms = dict(self.terms)
        for k, v in other.terms.items():
            terms[k] = terms.get(k, 0.0) + v
        return Expr(terms, self.const + other.const)

    __radd__ = __add__

    def __neg__(self) -> Expr:
        return Expr({k: -v for k, v in self.terms.items()}, -self.const)

    def __sub__(self, other) -> Expr:
        return self + (-(other if isinstance(other, Expr) else Expr(const=float(other))))

    def __rsub__(self, other) -> Expr:
        return (-self) + other

    def __mul__(self, k: float) -> Expr:
        return Expr({n: v * k for n, v in self.terms.items()}, self.const * k)

    __rmul__ = __mul__


Le = Expr  # a row "expr <= 0"


@dataclass
class Var:
    name: str
    lo: float
    hi: float
    binary: bool


@dataclass
class Model:
    vars: dict[str, Var] = field(default_factory=dict)
    hard: list[tuple[list[str], list[Le]]] = field(default_factory=list)  # (if all these binaries = 1) -> rows
    choices: list[tuple[list[str], list[list[Le]], list[str]]] = field(default_factory=list)  # cond -> any group
    objective: Expr = field(default_factory=Expr)
    goals: dict[str, bool] = field(default_factory=dict)  # each soft goal's binary -> is it a constraint?

    def var(self, name: str, lo: float, hi: float, binary: bool = False) -> Expr:
        self.vars[name] = Var(name, lo, hi, binary)
        return Expr({name: 1.0})

    def binary(self, name: str) -> Expr:
        return self.var(name, 0.0, 1.0, binary=True)

    def require(self, rows: list[Le], when: list[str] = ()) -> None:
        """rows hold whenever every binary in `when` is 1."""
        self.hard.append((list(when), rows))

    def any_of(self, groups: list[list[Le]], when: list[str], tag: str) -> None:
        """At least one group of rows holds whenever every binary in `when` is 1."""
        names = [f"{tag}.{k}" for k in range(len(groups))]
        for n in names:
            self.binary(n)
        self.choices.append((list(when), groups, names))

    def soft(self, name: str, rows_per_case: list[tuple[list[str], list[Le]]], weight: float,
             needs: list[str], constraint: bool = True) -> None:
        """Binary `name` may be 1 only if the objects in `needs` are placed and, for each case, its rows hold
        (`constraint`: one of the plan's constraints, not a clearance)."""
        s = self.binary(name)
        self.goals[name] = constraint
        for n in needs:
            self.require([s - Expr({n: 1.0})])
        for when, rows in rows_per_case:
            self.require(rows, when=[name, *when])
        self.objective = self.objective + (1 - s) * weight

    def pinned(self, values: dict[str, float], tol: float) -> Model:
        """The model with `values` put in for their variables (each then bounded to its value): a row left with no
        variable is decided (it holds when at most `tol`) and dropped with what it decides, so that the solver
        searches only what the free variables leave open. A decided row that fails makes its condition false."""
        def put(e: Expr) -> Expr:
            return Expr({n: c for n, c in e.terms.items() if n not in values},
                        e.const + sum(c * values[n] for n, c in e.terms.items() if n in values))

        def rows(rs: list[Le]) -> list[Le] | None:  # None: a row fails
            out = [put(r) for r in rs]
            if any(not r.terms and r.const > tol for r in out):
                return None
            return [r for r in out if r.terms]

        def cond(when: list[str]) -> list[str] | None:  # None: the condition cannot hold
            return None if any(values.get(n, 1.0) < 0.5 for n in when) else [n for n in when if n not in values]

        m = Model({n: Var(n, values[n], values[n], v.binary) if n in values else v for n, v in self.vars.items()},
                  objective=put(self.objective), goals=self.goals)
        for when, rs in self.hard:
            when, rs = cond(when), rows(rs)
            if when is not None and rs != []:
                m.hard.append((when, rs if rs is not None else [Expr(const=1.0)]))
        for when, groups, names in self.choices:
            when = cond(when)
            kept = [(n, g) for n, g in zip(names, map(rows, groups)) if g is not None]
            if when is None or any(not g for _, g in kept):
                continue  # no condition, or a group that holds already
            if kept:
                m.choices.append((when, [g for _, g in kept], [n for n, _ in kept]))
            else:
                m.hard.append((when, [Expr(const=1.0)]))
        return m

    def bound(self, e: Expr) -> float:
        """Largest value the expression can take over the variables' boxes (for big-M)."""
        return e.const + sum(v * (self.vars[k].hi if v > 0 else self.vars[k].lo) for k, v in e.terms.items())


# ---- building the placement model ------------------------------------------------------------------

def _half(o: PlanObject, k: int) -> tuple[float, float]:
    return (o.size.x / 2, o.size.z / 2) if k % 2 == 0 else (o.size.z / 2, o.size.x / 2)


FRONT = {0: (0, 1), 1: (1, 0), 2: (0, -1), 3: (-1, 0)}  # rotation index -> front (x, z)


@dataclass
class ObjVars:
    obj: PlanObject
    x: Expr
    z: Expr
    rot: list[str]
    placed: str
    hx: Expr
    hz: Expr


def build(problem: PlacementProblem, seed: int = 0, round_gaps: bool = False) -> tuple[Model, dict[str, ObjVars]]:
    """The model of `problem` (`seed`: its tie-break); with `round_gaps`, `near` and `around` hold within an octagon
    inscribed in the judge's circle of box gaps instead of the square the baselines' model uses, which misses
    about a quarter of the `near` the judge counts as met."""
    room = problem.plan.room
    W, D = room.width, room.depth
    m = Model()
    rng = random.Random(seed)
    ov: dict[str, ObjVars] = {}
    for o in problem.order:
        p = f"p[{o.id}]"
        m.binary(p)
        rot = [f"r[{o.id},{k}]" for k in range(4)]
        for r in rot:
            m.binary(r)
        x, z = m.var(f"x[{o.id}]", 0, W), m.var(f"z[{o.id}]", 0, D)
        if o.id in problem.fixed:  # a kept pose: pin its variables (to within rounding of stored poses)
            fx, fz, fr = problem.fixed[o.id]
            m.vars[f"x[{o.id}]"] = Var(f"x[{o.id}]", max(0.0, fx - PIN), min(W, fx + PIN), False)
            m.vars[f"z[{o.id}]"] = Var(f"z[{o.id}]", max(0.0, fz - PIN), min(D, fz + PIN), False)
            m.vars[p] = Var(p, 1.0, 1.0, True)
            k_fixed = int(round(fr / 90.0)) % 4
            for k, r in enumerate(rot):
                m.vars[r] = Var(r, float(k == k_fixed), float(k == k_fixed), True)
        hx = sum((Expr({rot[k]: _half(o, k)[0]}) for k in range(4)), Expr())
        hz = sum((Expr({rot[k]: _half(o, k)[1]}) for k in range(4)), Expr())
        m.require([sum((Expr({r: 1.0}) for r in rot), Expr()) - Expr({p: 1.0}),
                   Expr({p: 1.0}) - sum((Expr({r: 1.0}) for r in rot), Expr())])  # one rotation iff placed
        m.require([hx - x, x + hx - W, hz - z, z + hz - D])  # inside the room
        m.objective = m.objective + (1 - Expr({p: 1.0})) * UNPLACED_COST[o.is_task]
        m.objective = m.objective + x * rng.uniform(-1e-4, 1e-4) + z * rng.uniform(-1e-4, 1e-4)  # seeded tie-break
        ov[o.id] = ObjVars(o, x, z, rot, p, hx, hz)

    ids = list(ov)
    for i, a in enumerate(ids):
        A = ov[a]
        for b in ids[i + 1:]:
            B = ov[b]
            m.any_of(_apart(A, B, 0.0), when=[A.placed, B.placed], tag=f"sep[{a},{b}]")
        for n, d in enumerate(room.doors):
            lo, hi = d.center - d.width / 2 - 0.05, d.center + d.width / 2 + 0.05
            zone = {"south": (lo, 0, hi, DOOR_CLEARANCE), "north": (lo, D - DOOR_CLEARANCE, hi, D),
                    "west": (0, lo, DOOR_CLEARANCE, hi), "east": (W - DOOR_CLEARANCE, lo, W, hi)}[d.wall]
            m.any_of([[A.x + A.hx - zone[0]], [zone[2] - (A.x - A.hx)], [A.z + A.hz - zone[1]],
                      [zone[3] - (A.z - A.hz)]], when=[A.placed], tag=f"door[{a},{n}]")
        _globals(m, A, problem.constraints.objects[a].placement, W, D)
        for n, c in enumerate(problem.constraints.objects[a].relations):
            if c.target in ov:
                _relation(m, A, ov[c.target], c.name, f"rel[{a},{n}]", round_gaps)
        depth = problem.clearance.get(a, 0.0)
        if depth > 0:
            others = [ov[b] for b in ids if b != a and not problem.constraints.tied(a, b)]
            _clearance(m, A, others, depth, W, D)
    return m, ov


def pins(problem: PlacementProblem, ov: dict[str, ObjVars]) -> dict[str, float]:
    """The values of the kept poses' variables (`Model.pinned`): position, rotation, placed."""
    values = {}
    for oid, (x, z, r) in problem.fixed.items():
        k = int(round(r / 90.0)) % 4
        values |= {f"x[{oid}]": x, f"z[{oid}]": z, ov[oid].placed: 1.0}
        values |= {name: float(i == k) for i, name in enumerate(ov[oid].rot)}
    return values


def _apart(A: ObjVars, B: ObjVars, gap: float) -> list[list[Le]]:
    """The four ways two boxes can be `gap` apart: A left of, right of, below or above B."""
    return [[A.x + A.hx + gap - (B.x - B.hx)], [B.x + B.hx + gap - (A.x - A.hx)],
            [A.z + A.hz + gap - (B.z - B.hz)], [B.z + B.hz + gap - (A.z - A.hz)]]


def _globals(m: Model, A: ObjVars, placement: str, W: float, D: float) -> None:
    oid = A.obj.id
    if placement == "edge":  # back against the wall behind, per rotation
        back = {0: A.z - A.hz - EDGE_TOL, 1: A.x - A.hx - EDGE_TOL, 2: (D - EDGE_TOL) - (A.z + A.hz),
                3: (W - EDGE_TOL) - (A.x + A.hx)}
        cases = [([A.rot[k]], [back[k]]) for k in range(4)]
    else:
        cases = [([], [MIDDLE_MIN - (A.x - A.hx), A.x + A.hx - (W - MIDDLE_MIN), MIDDLE_MIN - (A.z - A.hz),
                       A.z + A.hz - (D - MIDDLE_MIN)])]
    m.soft(f"g[{oid}]", cases, GLOBAL_WEIGHT, needs=[A.placed])


def _relation(m: Model, A: ObjVars, B: ObjVars, name: str, tag: str, round_gaps: bool = False) -> None:
    dx, dz = A.x - B.x, A.z - B.z
    needs = [A.placed, B.placed]
    if name in ("near", "around"):
        gx = [(A.x - A.hx) - (B.x + B.hx), (B.x - B.hx) - (A.x + A.hx)]  # the gap along x is the larger, or 0
        gz = [(A.z - A.hz) - (B.z + B.hz), (B.z - B.hz) - (A.z + A.hz)]
        if round_gaps:
            rows = _octagon(gx, gz, NEAR_MAX if name == "near" else AROUND_MAX_GAP)
        else:
            rows = [g - (NEAR_LINF if name == "near" else AROUND_LINF) for g in gx + gz]
        m.soft(tag, [([], rows)], RELATION_WEIGHT, needs)
        if name == "around":
            _relation(m, A, B, "face to", tag + "f")
        return
    if name == "far":
        s = f"{tag}"
        m.soft(s, [], RELATION_WEIGHT, needs)
        m.any_of(_apart(A, B, FAR_MIN), when=[s], tag=tag + "d")
        return
    if name == "face to":  # A's front within 45 degrees of the direction to B, per rotation of A
        cases = []
        for k in range(4):
            fx, fz = FRONT[k]
            toward = -dx * fx - dz * fz  # (B - A) along A's front
            across = -dx * fz + dz * fx  # (B - A) along A's right
            cases.append(([A.rot[k]], [across - toward, -across - toward]))
        m.soft(tag, cases, RELATION_WEIGHT, needs)
        return
    if name == "face same as":
        m.soft(tag, [([A.rot[k]], [Expr({B.rot[k]: -1.0}) + 1]) for k in range(4)], RELATION_WEIGHT, needs)
        return
    if name == "center aligned":
        s = tag
        m.soft(s, [], RELATION_WEIGHT, needs)
        m.any_of([[dx - ALIGN_TOL, -dx - ALIGN_TOL], [dz - ALIGN_TOL, -dz - ALIGN_TOL]], when=[s], tag=tag + "a")
        return
    # directional relations, in B's frame, per rotation k of B
    cases = []
    for k in range(4):
        fx, fz = FRONT[k]
        ahead = dx * fx + dz * fz  # A's centre along B's front
        lateral = dx * fz - dz * fx  # along B's right (cos r, -sin r)
        bw, bd = B.obj.size.x / 2, B.obj.size.z / 2
        # box gap along B's front / side axis, from A's and B's half extents in world axes
        a_along = A.hz if fx == 0 else A.hx
        a_across = A.hx if fx == 0 else A.hz
        if name in ("in front of", "behind"):
            sign = 1 if name == "in front of" else -1
            rows = [bd - sign * ahead, sign * ahead - bd - a_along - FRONT_MAX_GAP, lateral - bw - LATERAL_SLACK,
                    -lateral - bw - LATERAL_SLACK]
            cases.append(([B.rot[k]], rows))
        else:  # side of, left of, right of
            sides = {"right of": [1], "left of": [-1], "side of": [1, -1]}[name]
            for sg in sides:
                rows = [bw - sg * lateral, sg * lateral - bw - a_across - SIDE_MAX_GAP, ahead - bd - LATERAL_SLACK,
                        -ahead - bd - LATERAL_SLACK]
                cases.append(([B.rot[k], f"{tag}.side{sg}"], rows))
    if name == "side of":
        m.binary(f"{tag}.side1")
        m.binary(f"{tag}.side-1")
        m.require([Expr({f"{tag}.side1": 1.0, f"{tag}.side-1": 1.0}) - 1])
        m.require([Expr({f"{tag}.side1": -1.0, f"{tag}.side-1": -1.0}) + 1])
    elif name in ("left of", "right of"):
        sg = 1 if name == "right of" else -1
        m.var(f"{tag}.side{sg}", 1.0, 1.0, binary=True)
    m.soft(tag, cases, RELATION_WEIGHT, needs)


def _octagon(gx: list[Expr], gz: list[Expr], radius: float) -> list[Le]:
    """Rows keeping the gap (max(0, *gx), max(0, *gz)) within the regular octagon inscribed in the circle of
    `radius`: each side's line for every choice of the two maxima's terms (those with a 0 follow from the first
    rows)."""
    c = math.cos(math.pi / 4)
    return [g - radius for g in gx + gz] + [row for a in gx for b in gz for row in
                                             (a * c + b * (1 - c) - radius * c, a * (1 - c) + b * c - radius * c)]


def _clearance(m: Model, A: ObjVars, others: list[ObjVars], depth: float, W: float, D: float) -> None:
    """Soft: the rectangle of `depth` in front of A stays inside the room and free of other objects."""
    cases = []
    for k in range(4):
        fx, fz = FRONT[k]
        hx, hz = _half(A.obj, k)
        off = (hz if fx == 0 else hx) + depth / 2
        cx, cz = A.x + fx * off, A.z + fz * off
        zx, zz = (hx, depth / 2) if fx == 0 else (depth / 2, hz)
        cases.append(([A.rot[k]], [zx - cx, cx + zx - W, zz - cz, cz + zz - D]))
        for B in others:
            m.any_of([[cx + zx - (B.x - B.hx)], [B.x + B.hx - (cx - zx)], [cz + zz - (B.z - B.hz)],
                      [B.z + B.hz - (cz - zz)]], when=[f"c[{A.obj.id}]", A.rot[k], B.placed],
                     tag=f"clr[{A.obj.id},{B.obj.id},{k}]")
    m.soft(f"c[{A.obj.id}]", cases, CLEARANCE_WEIGHT, needs=[A.placed], constraint=False)



class ModelSolver:
    """What the MILP and Z3 placers share: build the model, solve it within the budget, read the poses."""

    name = "model"
    no_solution = "no solution within the time budget"

    def __init__(self, time_budget_s: float | None = None):
        self.time_budget_s = time_budget_s  # None: the shared per-object rule (problem.time_budget)

    def solve(self, plan: ConstraintPlan, seed: int = 0, time_budget_s: float | None = None,
              observer=None, fixed: dict[str, tuple[float, float, float]] | None = None) -> Layout:
        start = time.perf_counter()
        problem = PlacementProblem.from_plan(plan, fixed)
        model, ov = build(problem, seed)
        budget = time_budget(plan, time_budget_s if time_budget_s is not None else self.time_budget_s)
        remaining = max(0.05, budget - (time.perf_counter() - start))
        poses, reasons = self.run(model, ov, seed, remaining)
        if problem.fixed and not poses:  # the kept poses cannot be completed: place everything afresh
            problem = PlacementProblem.from_plan(plan)
            model, ov = build(problem, seed)
            poses, reasons = self.run(model, ov, seed, max(0.05, budget - (time.perf_counter() - start)))
        if observer is not None:  # a whole-model solver has no steps: replay its answer in placement order
            for o in problem.order:
                x, z, r = poses.get(o.id, (None, None, None))
                observer(PlacementStep(o.id, x, z, r, np.empty((0, 3)), np.empty(0), {}))
        return make_layout(problem, poses, reasons, self.name, seed, time.perf_counter() - start,
                           default_reason=self.no_solution)

    def run(self, model: Model, ov: dict[str, ObjVars], seed: int, seconds: float
            ) -> tuple[dict[str, tuple[float, float, float]], dict[str, str]]:
        """(object id -> (x, z, rotation), object id -> why it is left out)."""
        raise NotImplementedError
