"""The paper's placement table: every solver on a constraint dataset, mean +- std over seeds.

    h3ds bench placement --dataset seen --n 40 --seeds 5   (default: DFS, MILP, Z3, greedy and Plan2Place)

For each seed and solver, every plan is solved and scored (models.metrics); a seed's figure is the
mean over plans, and the table shows the mean and standard deviation of those over seeds. Raw
per-plan results go to JSON and CSV, with PNG plots of time per scene against object count and of
the metric distributions.

Fairness (issue 7): every solver gets the same budget rule (models.placement.problem.time_budget,
0.5 s per plan object, unless --budget is given); SR and Key_NAV are averaged over the plans that have
task objects (the table says how many are n/a); a second table repeats the metrics over the (plan,
seed) pairs that every solver placed completely, so that leaving objects out never looks better. Any
solver registered in models.placement.base runs by name.
"""

from __future__ import annotations

import csv
import json
import statistics
import sys
import time
from pathlib import Path

from models.datasets import load_dataset
from models.energy.exact import layout_energy
from models.metrics import scene_metrics
from models.placement import PlacementProblem, get_solver
from models.placement.problem import PER_OBJECT_BUDGET_S

DEFAULT_SOLVERS = "dfs,milp,z3,greedy,plan2place"  # issue 8's full table: the baselines, the yardstick, the agent
COLUMNS = [("cnt", "CNT", 100), ("sr", "SR", 100), ("nav", "NAV", 100), ("key_nav", "Key_NAV", 100),
           ("oob", "OOB", 100), ("pto", "PTO (s)", 1), ("collisions", "collisions", 1),
           ("constraint_satisfaction", "constraints", 100), ("realism", "realism", 100), ("energy", "energy", 1)]


def pick_records(dataset: str, n: int):
    """`n` records evenly spaced over the set (the `seen` validation split)."""
    split = "validation" if dataset == "seen" else None
    records = load_dataset(dataset, split)
    step = max(len(records) // n, 1)
    return records[::step][:n]


def score(plan, layout) -> dict:
    """Every metric of one layout, its energy (the RL objective, here a judge) and why objects are missing."""
    from models.metrics.realism import realism
    problem = PlacementProblem.from_plan(plan)
    m = scene_metrics(plan, layout, problem)
    return {**m.as_dict(), "realism": realism(plan, layout),
            "energy": layout_energy(plan, layout.placements, problem).total,
            "unplaced": {u.id: u.reason for u in layout.unplaced}}


_solvers: dict = {}  # one instance per solver name per worker process


def solve_and_score(task: tuple) -> dict:
    """One (solver, seed, plan) run and its scores: the unit of work an executor runs."""
    dataset, solver_name, seed, plan, budget = task
    if solver_name not in _solvers:
        _solvers[solver_name] = get_solver(solver_name)
    solver = _solvers[solver_name]
    layout = solver.solve(plan, seed=seed, time_budget_s=budget)
    return {"dataset": dataset, "solver": solver_name, "seed": seed, "plan": plan.id, **score(plan, layout)}


def run(dataset: str, solvers: list[str], n: int, seeds: int, budget: float | None, executor=None) -> list[dict]:
    """Every solver x seed x plan; through `executor` (app.batch.executors; default: this process), rows
    in that order whatever order the runs finish in. Workers share the CPUs: PTO grows with --workers.
    The runs are handed out seed by seed, plan by plan, the solvers in turn (`turns`), so that every solver
    meets the same drift of the machine's speed and the same mix of runs on the other workers."""
    from app.batch.executors import InProcess
    records = pick_records(dataset, n)
    plans = [r.plan for r in records]
    rows = []
    # the `human` set keeps the arrangement people made: scored as a row of its own, like a solver
    for seed in range(seeds):
        rows.extend({"dataset": dataset, "solver": "human", "seed": seed, "plan": r.plan.id,
                     **score(r.plan, r.reference)} for r in records if r.reference is not None)
    tasks = [(dataset, s, seed, plan, budget) for s in solvers for seed in range(seeds) for plan in plans]
    runs, start = {}, time.perf_counter()
    order = turns(len(solvers), seeds * len(plans))
    for done in (executor or InProcess()).run(solve_and_score, [tasks[i] for i in order]):
        i = order[done.index]
        if done.error:
            raise RuntimeError(f"{tasks[i][1]} on {tasks[i][3].id}: {done.error}")
        runs[i] = done.value
        eta = (time.perf_counter() - start) / len(runs) * (len(tasks) - len(runs))
        print(f"\r  {dataset}: {done.value['solver']} seed {done.value['seed'] + 1}/{seeds} plan {len(runs)}/"
              f"{len(tasks)} (~{eta / 60:.1f} min left)   ", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    return rows + [runs[i] for i in range(len(tasks))]


def turns(solvers: int, runs: int) -> list[int]:
    """Indices into the solver-major task list (each solver's `runs` in a block) that take the solvers in turn,
    run by run. Handed out in blocks, a solver's times would hang on what the machine did during its block (its
    speed moves by up to 1.8 x for seconds at a time) and on the solver beside it on the other worker (itself),
    and a ratio of two solvers' times would mix both in."""
    return [s * runs + k for k in range(runs) for s in range(solvers)]


def complete_everywhere(rows: list[dict], solvers: list[str]) -> set[tuple[str, int]]:
    """(plan, seed) pairs that every solver placed completely."""
    done: dict[tuple[str, int], set[str]] = {}
    for r in rows:
        if r["complete"]:
            done.setdefault((r["plan"], r["seed"]), set()).add(r["solver"])
    return {k for k, v in done.items() if v >= set(solvers)}


def table(rows: list[dict], solvers: list[str]) -> str:
    """Mean +- std over seeds of the per-seed means; n/a values (None) are left out and counted."""
    head = "| solver | " + " | ".join(label for _, label, _ in COLUMNS) + " | n/a (SR / realism) |"
    lines = [head, "|" + " --- |" * (len(COLUMNS) + 2)]
    for solver in solvers:
        mine = [r for r in rows if r["solver"] == solver]
        seeds = sorted({r["seed"] for r in mine})
        cells = []
        for key, _, scale in COLUMNS:
            per_seed = []
            for s in seeds:
                values = [r[key] for r in mine if r["seed"] == s and r[key] is not None]
                if values:
                    per_seed.append(statistics.mean(values) * scale)
            if not per_seed:
                cells.append("n/a")
                continue
            sd = statistics.stdev(per_seed) if len(per_seed) > 1 else 0.0
            digits = 4 if key == "pto" else 2
            cells.append(f"{statistics.mean(per_seed):.{digits}f} +- {sd:.{digits}f}")
        na = f"{sum(r['sr'] is None for r in mine)} / {sum(r['realism'] is None for r in mine)} of {len(mine)}"
        lines.append(f"| {solver} | " + " | ".join(cells) + f" | {na} |")
    return "\n".join(lines)


def report(rows: list[dict], solvers: list[str], dataset: str, n_plans: int, seeds: int) -> str:
    both = complete_everywhere(rows, solvers)
    subset = [r for r in rows if (r["plan"], r["seed"]) in both]
    budget_over = max((r["time_s"] / (PER_OBJECT_BUDGET_S * r["n_objects"]) for r in rows), default=0.0)
    empty = {s: sum(not r["cnt"] for r in rows if r["solver"] == s) for s in solvers}
    out = [f"placement on `{dataset}` ({n_plans} plans x {seeds} seeds; metrics x100 except PTO (s per "
           f"object), collisions (per scene) and energy):", "", "all runs:", "", table(rows, solvers), "",
           f"runs every solver placed completely ({len(both)} of {n_plans * seeds} plan-seed pairs):", "",
           table(subset, solvers) if subset else "(none)", "",
           "runs that placed nothing: " + ", ".join(f"{s} {empty[s]}" for s in solvers)
           + f"; slowest run / per-object budget rule: {budget_over:.2f}"]
    return "\n".join(out)


def plots(rows: list[dict], solvers: list[str], out: Path, dataset: str) -> list[Path]:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = []
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.5), sharey=True)
    for ax, (label, test) in zip(axes, (("<= 10 objects", lambda k: k <= 10), ("> 10 objects", lambda k: k > 10))):
        means = [statistics.mean([r["time_s"] for r in rows if r["solver"] == s and test(r["n_objects"])] or [0])
                 for s in solvers]
        ax.bar(solvers, means, color=[["#888", "#4a7", "#47a", "#c44", "#a7c", "#ca4"][i % 6] for i in range(len(solvers))])
        ax.set_title(f"{dataset}: {label}")
        ax.set_ylabel("mean time per scene (s)")
        ax.tick_params(axis="x", labelrotation=35)
    fig.tight_layout()
    paths.append(out / "time_per_scene.png")
    fig.savefig(paths[-1], dpi=110)
    plt.close(fig)

    keys = [("cnt", "CNT"), ("key_nav", "Key_NAV"), ("constraint_satisfaction", "constraints"), ("nav", "NAV")]
    fig, axes = plt.subplots(1, len(keys), figsize=(12, 3.6))
    for ax, (key, label) in zip(axes, keys):
        ax.boxplot([[r[key] for r in rows if r["solver"] == s and r[key] is not None] or [0] for s in solvers],
                   tick_labels=solvers)
        ax.tick_params(axis="x", labelrotation=35)
        ax.set_title(label)
    fig.tight_layout()
    paths.append(out / "metric_distributions.png")
    fig.savefig(paths[-1], dpi=110)
    plt.close(fig)
    return paths


def stored_rows(out: Path, args) -> list[dict]:
    """The rows of a stored run in `out` that `--update` re-runs some solvers of: the same plans and seeds, or an
    error that names the difference (nothing is written then)."""
    path = out / "results.json"
    if not path.exists():
        raise SystemExit(f"--update: no stored run in {out} (results.json is missing); run the bench there first")
    rows = json.loads(path.read_text())
    wanted = {(r.plan.id, seed) for r in pick_records(args.dataset, args.n) for seed in range(args.seeds)}
    have = {(r["plan"], r["seed"]) for r in rows}
    if {r["dataset"] for r in rows} != {args.dataset} or have != wanted:
        raise SystemExit(f"--update: {path} holds other runs ({len(have)} plan-seed pairs of "
                         f"{sorted({r['dataset'] for r in rows})}) than --dataset {args.dataset} --n {args.n} "
                         f"--seeds {args.seeds} ({len(wanted)})")
    return rows


def merged(stored: list[dict], fresh: list[dict], solvers: list[str]) -> list[dict]:
    """The stored rows with those of `solvers` swapped for the fresh ones, in the stored order (a solver new to
    the run goes last)."""
    new = {s: [r for r in fresh if r["solver"] == s] for s in solvers}
    rows, placed = [], set()
    for r in stored:
        if r["solver"] not in new:
            rows.append(r)
        elif r["solver"] not in placed:
            rows.extend(new[r["solver"]])
            placed.add(r["solver"])
    return rows + [r for s in solvers if s not in placed for r in new[s]]


def main(args) -> int:
    solvers = [s.strip() for s in (args.solvers or DEFAULT_SOLVERS).split(",") if s.strip()]
    for s in solvers:
        get_solver(s)  # unknown names fail here, before any work
    out = Path(args.out or f"out/bench/placement-{args.dataset}")
    stored = stored_rows(out, args) if getattr(args, "update", False) else None
    out.mkdir(parents=True, exist_ok=True)
    from app.batch.executors import executor_from_args
    with executor_from_args(args, serial_default=True) as executor:
        rows = run(args.dataset, solvers, args.n, args.seeds, args.budget, executor)
    note = ""
    if stored is not None:
        rows = merged(stored, rows, solvers)
        note = (f"\n\n{', '.join(solvers)} re-run on {time.strftime('%Y-%m-%d')} (`--update`); the other solvers' "
                "rows are the stored ones")
    solvers = list(dict.fromkeys(r["solver"] for r in rows))
    (out / "results.json").write_text(json.dumps(rows, indent=1))
    with open(out / "results.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    pngs = plots(rows, solvers, out, args.dataset)
    text = report(rows, solvers, args.dataset, len({r["plan"] for r in rows}), args.seeds) + note
    (out / "table.md").write_text(text + "\n")
    print(text)
    print(f"\nraw results: {out / 'results.json'}, {out / 'results.csv'}; plots: {', '.join(str(p) for p in pngs)}")
    return 0


SETS = [("seen", "the validation split: instructions never seen in training"), ("unseen_a", "smaller, denser, misspelled"),
        ("unseen_b", "larger, sparser, respelled ids"), ("dense", "rooms 50-65 % full, random and conflicting relations"),
        ("human", "the iTHOR rooms; the row `human` is the arrangement people made")]


def pto_medians(root: Path) -> str:
    """Median PTO (ms per object) of each solver on each set, and its ratio to DFS's, from the stored raw
    results (the tables give the mean of per-seed means)."""
    sets = [name for name, _ in SETS if (root / f"placement-{name}" / "results.json").exists()]
    rows = {name: json.loads((root / f"placement-{name}" / "results.json").read_text()) for name in sets}
    solvers = [s for s in dict.fromkeys(r["solver"] for rs in rows.values() for r in rs) if s != "human"]
    lines = ["| solver | " + " | ".join(sets) + " |", "|" + " --- |" * (len(sets) + 1)]
    for solver in solvers:
        cells = []
        for name in sets:
            med = {s: statistics.median(r["pto"] for r in rows[name] if r["solver"] == s) for s in (solver, "dfs")}
            cells.append(f"{1000 * med[solver]:.1f} ({med[solver] / med['dfs']:.2f} x dfs)")
        lines.append(f"| {solver} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def replot(root: Path) -> list[Path]:
    """The plots of every stored set again, from its `results.json` (no run): after a change to `plots`."""
    paths = []
    for name, _ in SETS:
        folder = root / f"placement-{name}"
        if (folder / "results.json").exists():
            rows = json.loads((folder / "results.json").read_text())
            paths += plots(rows, list(dict.fromkeys(r["solver"] for r in rows)), folder, name)
    return paths


def readme_section(root: Path) -> str:
    """The README's placement tables, pasted from the stored `table.md` of each set, and the median PTO from
    the stored raw results (never typed in)."""
    parts = []
    for name, note in SETS:
        path = root / f"placement-{name}" / "table.md"
        if path.exists():
            parts.append(f"**{name}** ({note}):\n\n" + path.read_text().split("\n", 2)[2].strip())
            plot = path.parent / "metric_distributions.png"
            if plot.exists():
                parts.append(f"![{name}: CNT, Key_NAV, constraints met and NAV per run, by solver]"
                             f"(app/bench/results/{plot.parent.name}/{plot.name})")
    parts.append("**PTO p50** (ms per object, median over the plan-seed runs of each set, with the runs "
                 "sharing two workers):\n\n" + pto_medians(root))
    return "\n\n".join(parts)
