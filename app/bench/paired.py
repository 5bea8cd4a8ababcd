"""Paired comparisons of two solvers on the same (plan, seed) runs: the mean difference and a 95 % bootstrap
interval over plans (plans resampled with their seeds kept together), so that a lead is called a lead only
when the interval is clear of 0."""

from __future__ import annotations

import numpy as np

DRAWS = 2000


def paired(rows: list[dict], metric: str, a: str, b: str) -> dict[str, list[float]]:
    """plan -> the differences a - b over its seeds, from rows with "solver", "plan", "seed" and `metric`
    (pairs where either value is missing are dropped)."""
    by = {(r["solver"], r["plan"], r["seed"]): r.get(metric) for r in rows}
    out: dict[str, list[float]] = {}
    for (solver, plan, seed), v in by.items():
        w = by.get((b, plan, seed))
        if solver == a and v is not None and w is not None:
            out.setdefault(plan, []).append(v - w)
    return out


def interval(diffs: dict[str, list[float]], rng: np.random.Generator) -> tuple[float, float, float]:
    """(mean difference, 2.5th and 97.5th percentiles of the plan-bootstrap means); nan when nothing pairs."""
    plans = list(diffs)
    if not plans:
        return float("nan"), float("nan"), float("nan")
    means = [np.mean([d for p in rng.choice(plans, len(plans)) for d in diffs[p]]) for _ in range(DRAWS)]
    return float(np.mean([d for p in plans for d in diffs[p]])), *(float(v) for v in np.percentile(means, [2.5, 97.5]))


def cell(mean: float, lo: float, hi: float, higher_is_better: bool, digits: int = 2) -> str:
    """"+0.12 [+0.03, +0.20]", bold when a is better with the interval clear of 0, italic when worse."""
    text = f"{mean:+.{digits}f} [{lo:+.{digits}f}, {hi:+.{digits}f}]"
    better, worse = (lo > 0, hi < 0) if higher_is_better else (hi < 0, lo > 0)
    return f"**{text}**" if better else f"_{text}_" if worse else text


def header(first: str, metrics) -> list[str]:
    """A paired table's two head lines: `first` column, then each metric (name, scale, higher is better, ...)."""
    return ["| " + first + " | " + " | ".join(f"{m[0]} ({'higher' if m[2] else 'lower'} is better)" for m in metrics)
            + " |", "| --- |" + " --- |" * len(metrics)]


def stored_table(results, sets, metrics, other, caption: str, name_other: bool = False, a: str = "plan2place") -> str:
    """A set x metric table of `a` - `other(rows, metric, higher_is_better)` (a solver's name) from the
    placement bench's stored runs (`results`/placement-<set>/results.json); `metrics`: (name, scale, higher is
    better, digits); with `name_other`, each cell names the solver it is paired with."""
    import json
    rng = np.random.default_rng(0)
    lines = [caption, "", *header("set", metrics)]
    for s in sets:
        rows = json.loads((results / f"placement-{s}" / "results.json").read_text())
        cells = []
        for metric, scale, up, digits in metrics:
            name = other(rows, metric, up)
            text = cell(*(scale * v for v in interval(paired(rows, metric, a, name), rng)), up, digits)
            cells.append(f"{text} vs {name}" if name_other else text)
        lines.append(f"| {s} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"
