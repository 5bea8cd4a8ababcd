"""Paired comparisons of two solvers on the same (plan, seed) runs: the mean difference and a 95 % bootstrap
interval over plans (plans resampled with their seeds kept together), so that a lead is called a lead only
when the interval is clear of 0."""

from __future__ import annotations

import hashlib
import json
import sys
import time

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
    """"+0.12 [+0.03, +0.20]", bold when a is better with the interval clear of 0, italic when worse; clear as
    shown: a bound that rounds to 0 at `digits` (a float sum's last bit) is not clear of it."""
    text = f"{mean:+.{digits}f} [{lo:+.{digits}f}, {hi:+.{digits}f}]"
    shown = 0.5 * 10.0 ** -digits
    better, worse = (lo >= shown, hi <= -shown) if higher_is_better else (hi <= -shown, lo >= shown)
    return f"**{text}**" if better else f"_{text}_" if worse else text


def header(first: str, metrics) -> list[str]:
    """A paired table's two head lines: `first` column, then each metric (name, scale, higher is better, ...)."""
    return ["| " + first + " | " + " | ".join(f"{m[0]} ({'higher' if m[2] else 'lower'} is better)" for m in metrics)
            + " |", "| --- |" + " --- |" * len(metrics)]


def stored_table(results, sets, metrics, other, caption: str, name_other: bool = False, a: str = "plan2place") -> str:
    """A set x metric table of `a` - `other(rows, metric, higher_is_better)` (a solver's name) from the
    placement bench's stored runs (`results`/placement-<set>/results.json); `metrics`: (name, scale, higher is
    better, digits); with `name_other`, each cell names the solver it is paired with."""
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


def alternating(plan_sets: dict, where, attribute: str, variants: dict, metrics,
                placers=("plan2place", "greedy")) -> list[dict]:
    """Each placer on each (plan, seed) of `plan_sets` (label -> (plans, seeds)) under every variant in turn, the
    variants' order reversed from run to run so that neither always runs on warm caches: one row per solve with the
    `metrics` of the placement judge (pto_ms: ms per object), "set", "placer", "solver" (the variant), "plan", "seed"
    and "layout" (a short hash of the poses). `variants`: name -> the value `where.attribute` takes in it (a module's
    constant or function); the value it had is put back at the end."""
    from app.bench.placement import score
    from models.placement.base import get_solver

    rows, k, shipped = [], 0, getattr(where, attribute)
    for label, (plans, seeds) in plan_sets.items():
        print(label, len(plans), "plans", file=sys.stderr, flush=True)
        for name in placers:
            solver = get_solver(name)
            for plan in plans:
                for seed in seeds:
                    k += 1
                    for variant in list(variants)[::1 if k % 2 else -1]:
                        setattr(where, attribute, variants[variant])
                        t = time.perf_counter()
                        layout = solver.solve(plan, seed=seed)
                        ms = 1000 * (time.perf_counter() - t) / len(plan.objects)
                        got = score(plan, layout)
                        rows.append({**{m: got.get(m) for m, *_ in metrics if m != "pto_ms"}, "pto_ms": ms,
                                     "set": label, "placer": name, "solver": variant, "plan": plan.id, "seed": seed,
                                     "layout": fingerprint(layout)})
    setattr(where, attribute, shipped)
    return rows


def fingerprint(layout) -> str:
    """A short hash of a layout's poses: enough to tell whether two layouts are the same."""
    poses = sorted((p.id, p.x, p.z, p.rotation) for p in layout.placements)
    return hashlib.sha1(repr(poses).encode()).hexdigest()[:12]


def store(folder, rows: list[dict], report: str) -> None:
    """An experiment's runs (`runs.json`) and report (`result.md`) beside its script, and the report printed."""
    (folder / "runs.json").write_text(json.dumps(rows))
    (folder / "result.md").write_text(report)
    print(report)


def variant_rows(rows: list[dict], old: str, new: str, metrics, placers=("plan2place", "greedy")) -> list[str]:
    """The rows of a table of `new` - `old` (two variants of `alternating`'s runs) per set and placer, each naming
    its runs and, where the runs carry their layouts, how many of those the variant left unchanged."""
    rng, lines = np.random.default_rng(0), []
    for label in dict.fromkeys(r["set"] for r in rows):
        for placer in placers:
            mine = [r for r in rows if r["set"] == label and r["placer"] == placer]
            count = f"{len({(r['plan'], r['seed']) for r in mine})} runs"
            if all("layout" in r for r in mine):
                layouts = {(r["plan"], r["seed"], r["solver"]): r["layout"] for r in mine}
                same = sum(layouts[(p, s, new)] == layouts[(p, s, old)] for p, s, v in layouts if v == old)
                count += f", {same} layouts unchanged"
            cells = [cell(*(sc * v for v in interval(paired(mine, m, new, old), rng)), up, d) for m, sc, up, d in metrics]
            lines.append(f"| {label} / {placer} ({count}) | " + " | ".join(cells) + " |")
    return lines
