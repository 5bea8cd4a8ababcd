"""The ablations with two training seeds each, judged in one bench run (`bench.sh` here): per configuration and set,
the two seeds' final energy, constraints met, Key_NAV and realism, how far the seeds lie apart (seed 1 - seed 0,
paired over the same plans and bench seeds, with the plans' 95 % bootstrap interval), and the configuration's two-seed
mean minus the full model's (cross-attention). A configuration difference no larger than the seeds' own spread says
nothing about the design choice. Reads the sets' results.json beside this script, writes summary.md:
PYTHONPATH=. python app/bench/results/plan2place/learning/ablations-seeds/summary.py"""

import json
from pathlib import Path

import numpy as np

from app.bench.paired import cell, interval, paired

HERE = Path(__file__).resolve().parent
SETS = ("seen", "unseen_a", "dense")
CONFIGS = {"cross": "cross-attention (full model)", "concat": "concatenation fusion", "self": "self-attention fusion",
           "noaux": "without the auxiliary loss", "nosff": "without SFF", "h64": "hidden 64", "h256": "hidden 256"}
METRICS = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2), ("key_nav", 100, True, 2),
           ("realism", 100, True, 2))


def name(config: str, seed: int) -> str:
    return f"abl-im-s{seed}-{config} (400 ep)"


def mean(rows: list[dict], solver: str, metric: str) -> float:
    return float(np.mean([r[metric] for r in rows if r["solver"] == solver and r[metric] is not None]))


def two_seed(rows: list[dict], config: str) -> list[dict]:
    """The rows of both seeds of `config` as one solver ("<config> seeds"), each (plan, seed) the seeds' mean."""
    by = {}
    for r in rows:
        for s in (0, 1):
            if r["solver"] == name(config, s):
                by.setdefault((r["plan"], r["seed"]), []).append(r)
    return [{**{m: _both(pair, m) for m, *_ in METRICS}, "solver": f"{config} seeds", "plan": plan, "seed": seed}
            for (plan, seed), pair in by.items() if len(pair) == 2]


def _both(pair: list[dict], metric: str) -> float | None:
    """The two seeds' mean of `metric`; None where the judge has no figure (realism with no check)."""
    values = [r[metric] for r in pair]
    return None if None in values else float(np.mean(values))


def table(rows: list[dict], metric: str, scale: float, up: bool, digits: int, rng) -> list[str]:
    lines = [f"**{metric}** ({'higher' if up else 'lower'} is better; x {scale:g})", "",
             "| configuration | seed 0 | seed 1 | seed 1 - seed 0 | two-seed mean - full model's |",
             "| --- | --- | --- | --- | --- |"]
    merged = rows + [r for c in CONFIGS for r in two_seed(rows, c)]
    for config, label in CONFIGS.items():
        a, b = (scale * mean(rows, name(config, s), metric) for s in (0, 1))
        spread = cell(*(scale * v for v in interval(paired(rows, metric, name(config, 1), name(config, 0)), rng)),
                      up, digits)
        versus = "" if config == "cross" else cell(*(scale * v for v in interval(
            paired(merged, metric, f"{config} seeds", "cross seeds"), rng)), up, digits)
        lines.append(f"| {label} | {a:.{digits}f} | {b:.{digits}f} | {spread} | {versus} |")
    for solver in ("greedy", "plan2place_untrained"):
        lines.append(f"| {solver} | {scale * mean(rows, solver, metric):.{digits}f} | | | |")
    return lines


def compact(runs: dict[str, list[dict]]) -> list[str]:
    """One line per configuration: per set, the two seeds' energy and constraints met (x 100), "seed 0 / seed 1"."""
    lines = ["| configuration | " + " | ".join(f"`{s}`: energy; constraints" for s in SETS) + " |",
             "| --- |" + " --- |" * len(SETS)]
    for config, label in CONFIGS.items():
        cells = [f"{mean(runs[s], name(config, 0), 'energy'):.3f} / {mean(runs[s], name(config, 1), 'energy'):.3f}; "
                 f"{100 * mean(runs[s], name(config, 0), 'constraint_satisfaction'):.1f} / "
                 f"{100 * mean(runs[s], name(config, 1), 'constraint_satisfaction'):.1f}" for s in SETS]
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    for solver in ("greedy", "plan2place_untrained"):
        cells = [f"{mean(runs[s], solver, 'energy'):.3f}; {100 * mean(runs[s], solver, 'constraint_satisfaction'):.1f}"
                 for s in SETS]
        lines.append(f"| {solver} | " + " | ".join(cells) + " |")
    return lines


def main() -> str:
    rng = np.random.default_rng(0)
    runs = {s: json.loads((HERE / s / "results.json").read_text()) for s in SETS}
    out = [__doc__.split("\n\n")[0].replace("\n", " "), "", "Seed 0 / seed 1 (energy: lower is better):", "",
           *compact(runs), ""]
    for s in SETS:
        rows = runs[s]
        plans = len({r["plan"] for r in rows})
        out += [f"### `{s}` ({plans} plans x 3 bench seeds)", ""]
        for metric in METRICS:
            out += [*table(rows, *metric, rng), ""]
    return "\n".join(out)


if __name__ == "__main__":
    (HERE / "summary.md").write_text(text := main())
    print(text)
