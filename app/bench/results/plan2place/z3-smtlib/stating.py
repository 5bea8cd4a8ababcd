"""How long stating a placement model to Z3 takes: through the Python API, as smt.py at ab.BEFORE did (its
statements, read from git), against writing SMT-LIB text and Z3's parser (now); the same built models, the two in
turn, over the `unseen_a` bench sample's rooms of up to 9 objects (the exact finish's rooms) and all of them. Prints
and writes stating.txt beside this script:

    PYTHONPATH=. python app/bench/results/plan2place/z3-smtlib/stating.py
"""
import statistics
import time
from pathlib import Path

import z3

from app.bench.placement import pick_records
from models.placement.formulation import Expr, build
from models.placement.problem import PlacementProblem
from models.placement.smt import smtlib

HERE = Path(__file__).parent


def by_api(model) -> None:
    """The statements smt.py made before 5a8166f, one per Python API call."""
    ctx = z3.Context()
    v = {n: (z3.Int(n, ctx) if var.binary else z3.Real(n, ctx)) for n, var in model.vars.items()}

    def lin(e: Expr):
        return z3.Sum([z3.RealVal(0, ctx)] + [c * v[n] for n, c in e.terms.items()]) + e.const

    def on(names):
        return z3.And([v[n] == 1 for n in names]) if names else z3.BoolVal(True, ctx)

    opt = z3.Optimize(ctx=ctx)
    for n, var in model.vars.items():
        opt.add(v[n] >= var.lo, v[n] <= var.hi)
    for when, rows in model.hard:
        opt.add(z3.Implies(on(when), z3.And([lin(r) <= 0 for r in rows])))
    for when, groups, _ in model.choices:
        opt.add(z3.Implies(on(when), z3.Or([z3.And([lin(r) <= 0 for r in g]) for g in groups])))
    for n, coef in model.objective.terms.items():
        if model.vars[n].binary and coef < 0:
            opt.add_soft(v[n] == 1, weight=str(round(-coef, 4)))


def by_text(model) -> None:
    opt = z3.Optimize(ctx=z3.Context())
    opt.from_string(smtlib(model)[0])


def main() -> str:
    models = [(len(r.plan.objects), build(PlacementProblem.from_plan(r.plan), 0)[0])
              for r in pick_records("unseen_a", 100)]
    times = {"api": [], "text": []}
    for _, model in models:
        for name, state in (("api", by_api), ("text", by_text)):
            t = time.process_time()
            state(model)
            times[name].append(time.process_time() - t)
    lines = ["Stating a placement model to Z3, CPU ms per room (p50 / max), the two in turn on the same built models "
             f"of the `unseen_a` bench sample ({len(models)} rooms):", ""]
    for label, keep in (("rooms of up to 9 objects (the exact finish's)", lambda n: n <= 9), ("every room", None)):
        idx = [i for i, (n, _) in enumerate(models) if keep is None or keep(n)]
        api, text = ([1000 * times[k][i] for i in idx] for k in ("api", "text"))
        lines.append(f"- {label}, {len(idx)}: Python API {statistics.median(api):.0f} / {max(api):.0f}, "
                     f"SMT-LIB text {statistics.median(text):.1f} / {max(text):.1f}; "
                     f"{statistics.median(a / t for a, t in zip(api, text)):.0f} x faster at the median")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    text = main()
    (HERE / "stating.txt").write_text(text)
    print(text)
