"""The rule of decision.md: checkpoints of fit.py against the shipped weights, every placer with the repairs.

    PYTHONPATH=. python app/bench/results/plan2place/lookahead-critic/judge.py select CKPT.npz ...  # -> selection.md
    PYTHONPATH=. python app/bench/results/plan2place/lookahead-critic/judge.py fresh CKPT.npz       # -> fresh.md
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from models.placement.base import get_solver
from models.placement.plan2place.policy import NumpyPolicy, Weights
from models.placement.plan2place.solver import Plan2PlaceSolver, untrained_solver

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
from run import SETS, diagnosis_plans, mean_lines, paired_lines, runs  # noqa: E402  (lookahead-bound/run.py)

METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2), ("key_nav", 100, True, 2),
           ("cnt", 100, True, 2), ("realism", 100, True, 2))
SHIPPED = "plan2place"


def offset_plans(ds: str, fraction: str = "7/8") -> list:
    import importlib.util
    spec = importlib.util.spec_from_file_location("make_way_run", HERE.parent / "make-way-strips" / "run.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.plans(ds, fraction)


def solvers(ckpts: list[Path], baselines: bool) -> list:
    out = [get_solver(SHIPPED)]
    for c in ckpts:
        w = Weights.load(c)
        out.append(Plan2PlaceSolver(NumpyPolicy(w.arrays, w.net), name=c.stem, use_global=w.use_global))
    return out + ([get_solver("greedy"), untrained_solver()] if baselines else [])


def means(rows, ds, name, metric) -> float:
    return float(np.mean([r[metric] for r in rows if r["set"] == ds and r["solver"] == name]))


def main(mode: str, ckpts: list[Path], here: Path = HERE, fresh=offset_plans, tag: str = "") -> int:
    """Writes `here`/{select,fresh}{tag}-rows.json and selection{tag}.md / fresh{tag}.md; the fresh plans are
    `fresh(set)` (default: make-way-strips' at 7/8); in `fresh` mode the first checkpoint is judged and any others
    are only reported."""
    placers = solvers(ckpts, baselines=mode == "fresh")
    names = [s.name for s in placers]
    rows = runs((lambda ds: diagnosis_plans(ds, 16)) if mode == "select" else fresh, placers, METRICS)
    (here / f"{mode}{tag}-rows.json").write_text(json.dumps(rows) + "\n")
    lines = [*mean_lines(rows, names, METRICS), "", "Paired against the shipped weights (each minus shipped, 95 % "
             "plan-bootstrap interval; bold: better, italic: worse, clear of 0)", "",
             *paired_lines(rows, [(n, SHIPPED) for n in names[1:]], METRICS)]
    if mode == "select":
        def key(n):
            below = sum(means(rows, ds, n, "energy") < means(rows, ds, SHIPPED, "energy") for ds in SETS)
            return -below, np.mean([means(rows, ds, n, "energy") - means(rows, ds, SHIPPED, "energy") for ds in SETS])
        chosen = min((c.stem for c in ckpts), key=key)
        lines += ["", f"chosen by decision.md step 1: {chosen} (mean energy below the shipped weights' on "
                  f"{-key(chosen)[0]} of {len(SETS)} sets)"]
    else:
        n = ckpts[0].stem
        lower = sum(means(rows, ds, n, "energy") < means(rows, ds, SHIPPED, "energy") for ds in SETS)
        kept = all(means(rows, ds, n, "constraint_satisfaction") >= means(rows, ds, SHIPPED, "constraint_satisfaction")
                   - 0.005 and all(means(rows, ds, n, m) >= means(rows, ds, SHIPPED, m) for m in ("key_nav", "cnt"))
                   for ds in SETS)
        lines += ["", f"decision.md step 2: energy lower on {lower} of {len(SETS)} sets; constraints, Key_NAV and CNT "
                  f"kept: {kept}; ship: {lower >= 4 and kept}"]
    (here / f"{'selection' if mode == 'select' else 'fresh'}{tag}.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], [Path(p) for p in sys.argv[2:]]))
