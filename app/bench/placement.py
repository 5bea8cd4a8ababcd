"""The paper's placement table: every solver on a constraint dataset, mean +- std over seeds.

    h3ds bench placement --dataset seen --solvers dfs,milp,z3 --n 40 --seeds 5

For each seed and solver, every plan is solved and scored (models.metrics); a seed's figure is the
mean over plans, and the table shows the mean and standard deviation of those over seeds. Raw
per-plan results go to JSON and CSV, with PNG plots of time per scene against object count and of
the metric distributions.
"""

from __future__ import annotations

import csv
import json
import statistics
import sys
import time
from pathlib import Path

from models.datasets import load_dataset
from models.metrics import scene_metrics
from models.placement import PlacementProblem, get_solver

COLUMNS = [("cnt", "CNT", 100), ("sr", "SR", 100), ("nav", "NAV", 100), ("key_nav", "Key_NAV", 100),
           ("oob", "OOB", 100), ("pto", "PTO (s)", 1), ("collisions", "collisions", 1),
           ("constraint_satisfaction", "constraints", 100)]


def pick_plans(dataset: str, n: int):
    split = "validation" if dataset == "seen" else None
    records = load_dataset(dataset, split)
    step = max(len(records) // n, 1)
    return [r.plan for r in records[::step][:n]]


def run(dataset: str, solvers: list[str], n: int, seeds: int, budget: float | None) -> list[dict]:
    plans = pick_plans(dataset, n)
    rows = []
    total = len(solvers) * seeds * len(plans)
    done, start = 0, time.perf_counter()
    for solver_name in solvers:
        solver = get_solver(solver_name)
        for seed in range(seeds):
            for plan in plans:
                layout = solver.solve(plan, seed=seed, time_budget_s=budget)
                m = scene_metrics(plan, layout, PlacementProblem.from_plan(plan))
                rows.append({"dataset": dataset, "solver": solver_name, "seed": seed, "plan": plan.id, **m.as_dict()})
                done += 1
                eta = (time.perf_counter() - start) / done * (total - done)
                print(f"\r  {dataset}: {solver_name} seed {seed + 1}/{seeds} plan {done}/{total} "
                      f"(~{eta / 60:.1f} min left)   ", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    return rows


def table(rows: list[dict], solvers: list[str]) -> str:
    head = "| solver | " + " | ".join(label for _, label, _ in COLUMNS) + " |"
    lines = [head, "|" + " --- |" * (len(COLUMNS) + 1)]
    for solver in solvers:
        mine = [r for r in rows if r["solver"] == solver]
        seeds = sorted({r["seed"] for r in mine})
        cells = []
        for key, _, scale in COLUMNS:
            per_seed = [statistics.mean(r[key] for r in mine if r["seed"] == s) * scale for s in seeds]
            sd = statistics.stdev(per_seed) if len(per_seed) > 1 else 0.0
            cells.append(f"{statistics.mean(per_seed):.2f} +- {sd:.2f}" if scale != 1 or key != "pto"
                         else f"{statistics.mean(per_seed):.4f} +- {sd:.4f}")
        lines.append(f"| {solver} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def plots(rows: list[dict], solvers: list[str], out: Path, dataset: str) -> list[Path]:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = []
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.5), sharey=True)
    for ax, (label, test) in zip(axes, (("<= 10 objects", lambda k: k <= 10), ("> 10 objects", lambda k: k > 10))):
        means = [statistics.mean([r["time_s"] for r in rows if r["solver"] == s and test(r["n_objects"])] or [0])
                 for s in solvers]
        ax.bar(solvers, means, color=["#888", "#4a7", "#47a", "#c44"][:len(solvers)])
        ax.set_title(f"{dataset}: {label}")
        ax.set_ylabel("mean time per scene (s)")
    fig.tight_layout()
    paths.append(out / "time_per_scene.png")
    fig.savefig(paths[-1], dpi=110)
    plt.close(fig)

    keys = [("cnt", "CNT"), ("key_nav", "Key_NAV"), ("constraint_satisfaction", "constraints"), ("nav", "NAV")]
    fig, axes = plt.subplots(1, len(keys), figsize=(12, 3.2))
    for ax, (key, label) in zip(axes, keys):
        ax.boxplot([[r[key] for r in rows if r["solver"] == s] for s in solvers], tick_labels=solvers)
        ax.set_title(label)
    fig.tight_layout()
    paths.append(out / "metric_distributions.png")
    fig.savefig(paths[-1], dpi=110)
    plt.close(fig)
    return paths


def main(args) -> int:
    solvers = [s.strip() for s in args.solvers.split(",") if s.strip()]
    for s in solvers:
        get_solver(s)  # unknown names fail here, before any work
    out = Path(args.out or f"out/bench/placement-{args.dataset}")
    out.mkdir(parents=True, exist_ok=True)
    rows = run(args.dataset, solvers, args.n, args.seeds, args.budget)
    (out / "results.json").write_text(json.dumps(rows, indent=1))
    with open(out / "results.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    pngs = plots(rows, solvers, out, args.dataset)
    print(f"placement on `{args.dataset}` ({args.n} plans, {args.seeds} seeds; metrics x100 except PTO, "
          f"collisions per scene):\n")
    print(table(rows, solvers))
    print(f"\nraw results: {out / 'results.json'}, {out / 'results.csv'}; plots: {', '.join(str(p) for p in pngs)}")
    return 0
