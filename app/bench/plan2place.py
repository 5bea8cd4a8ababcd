"""Does the learning do something? Plan2Place checkpoints against the same network untrained and the
greedy placer, on the same plans in one run; also the ablation runs (each its own checkpoint).

    h3ds bench plan2place --dataset seen --n 40 --seeds 1 --runs models/weights/plan2place/plan2place.npz
    h3ds bench plan2place --runs runs/main,runs/noglobal,runs/nosff,runs/noaux,runs/concat,runs/h64
    h3ds bench plan2place --dataset varied --n 40 --seeds 1 --runs runs/varied/ckpt-01000.pt,...

`--dataset varied`: plans of the seen validation instructions in varied rooms (models.datasets.varied), which
no other benchmark uses: where checkpoints of a run are chosen.

A run is exported weights (.npz), a checkpoint file or a training folder (its checkpoint.pt). Figures:
the exact energy of the final layout (the RL objective; lower is better), the placement metrics x 100, PTO p50 per object.
"""

from __future__ import annotations

import json
import statistics
import time
from pathlib import Path

import numpy as np

from app.bench.paired import cell, header, interval, paired
from app.bench.placement import pick_records, score
from models.datasets.varied import NAME as VARIED, varied_plan
from models.placement import get_solver
from models.placement.greedy import GreedySolver

METRICS = [("energy", "energy", 1), ("cnt", "CNT", 100), ("sr", "SR", 100), ("key_nav", "Key_NAV", 100),
           ("nav", "NAV", 100), ("constraint_satisfaction", "constraints", 100), ("realism", "realism", 100),
           ("collisions", "collisions", 1)]


def shipped_path() -> str:
    """The shipped weights' file, wherever the command runs from."""
    from importlib import resources

    from models.placement.plan2place.policy import SHIPPED
    return str(resources.files("models").joinpath(SHIPPED))


def solver_for(run: str, repair: bool = True):
    from models.placement.plan2place.agent import fast_policy, load_run
    from models.placement.plan2place.solver import Plan2PlaceSolver
    path = Path(run)
    net, episodes = load_run(path)
    label = f"{path.name if path.is_dir() else path.stem} ({episodes} ep){'' if repair else ', no repair'}"
    return Plan2PlaceSolver(fast_policy(net), name=label, use_global=net.use_global, repair=repair)


def evaluate(solvers: list, plans: list, seeds: int | range) -> dict[str, list[dict]]:
    """Each solver's rows on `plans` x `seeds` (a count from 0, or the seeds themselves)."""
    rows: dict[str, list[dict]] = {}
    for solver in solvers:
        for seed in range(seeds) if isinstance(seeds, int) else seeds:
            for plan in plans:
                t = time.perf_counter()
                layout = solver.solve(plan, seed=seed)
                elapsed = time.perf_counter() - t
                rows.setdefault(solver.name, []).append({**score(plan, layout), "solver": solver.name,
                                                         "plan": plan.id, "seed": seed,
                                                         "pto_s": elapsed / max(len(plan.objects), 1)})
    return rows


PAIRED = (("energy", 1, False, 3), ("constraint_satisfaction", 100, True, 2), ("realism", 100, True, 2))


def paired_table(flat: list[dict], runs: list[str], baselines: list[str]) -> str:
    """Each trained run minus each baseline on the same (plan, seed) runs (`flat`: every solver's rows), with 95 %
    bootstrap intervals over plans (app.bench.paired): is a lead in the table above more than the plans' noise?"""
    rng, lines = np.random.default_rng(0), header("run - baseline", PAIRED)
    for run in runs:
        for base in baselines:
            cells = [cell(*(scale * v for v in interval(paired(flat, m, run, base), rng)), up, digits)
                     for m, scale, up, digits in PAIRED]
            lines.append(f"| {run} - {base} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def table(rows: dict[str, list[dict]]) -> str:
    head = "| solver | " + " | ".join(lbl for _, lbl, _ in METRICS) + " | PTO p50 (ms) |"
    lines = [head, "|" + " --- |" * (len(METRICS) + 2)]
    for name, rs in rows.items():
        cells = []
        for key, _, scale in METRICS:
            vals = [r[key] for r in rs if r.get(key) is not None]
            cells.append(f"{statistics.mean(vals) * scale:.2f}" if vals else "n/a")
        pto = 1000 * float(np.median([r["pto_s"] for r in rs]))
        lines.append(f"| {name} | " + " | ".join(cells) + f" | {pto:.1f} |")
    return "\n".join(lines)


def proof_solvers(runs: list[str]) -> tuple[list, list, list]:
    """The learning proof's solvers: (greedy and the untrained network, each of `runs`, and the placers alone
    without the repairs (models.placement.repair), where the policy's own choices show: greedy, the untrained
    network and the first run)."""
    from models.placement.plan2place.solver import untrained_solver
    return ([get_solver("greedy"), untrained_solver()], [solver_for(r) for r in runs],
            [GreedySolver(repair=False), untrained_solver(repair=False), solver_for(runs[0], repair=False)])


def main(args) -> int:
    if args.dataset == VARIED:
        plans = [varied_plan(0, e, "validation") for e in range(args.n)]
    else:
        plans = [r.plan for r in pick_records(args.dataset, args.n)]
    runs = [r for r in (args.runs or shipped_path()).split(",") if r]
    for run in runs:
        if not Path(run).exists():
            raise FileNotFoundError(2, "no such run (exported weights, checkpoint or training folder)", run)
    baselines, trained, bare = proof_solvers(runs)
    rows = evaluate(baselines + trained + bare, plans, args.seeds)
    flat = [r for rs in rows.values() for r in rs]
    text = (f"plan2place bench on {len(plans)} `{args.dataset}` plans x {args.seeds} seed(s); energy = exact "
            f"energy of the final layout (lower is better), metrics x 100\n\n{table(rows)}\n\n"
            f"paired on the same runs, mean difference [95 % bootstrap interval over plans]; **bold**: the run "
            f"is better with the interval clear of 0, _italic_: worse\n\n"
            f"{paired_table(flat, [s.name for s in trained], [s.name for s in baselines])}\n\n"
            f"{paired_table(flat, [bare[2].name], [s.name for s in bare[:2]])}\n")
    print(text)
    if args.out:
        Path(args.out).mkdir(parents=True, exist_ok=True)
        (Path(args.out) / "plan2place.md").write_text(text)
        (Path(args.out) / "results.json").write_text(json.dumps(flat))
    return 0


# ---- speed: PTO of dfs, greedy and plan2place on the same plans, in one process ----------------------

SPEED_SOLVERS = ("dfs", "greedy", "plan2place")
STEPPED = "+steps"  # a solver name with this suffix is timed through the step iterator (models.placement.stepping)


class _Stepped:
    """A solver run through `Stepping`, every step taken from the iterator: what the iterator costs."""

    def __init__(self, name: str):
        self.inner = get_solver(name)

    def solve(self, plan, seed: int = 0):
        from models.placement.stepping import Stepping
        stepping = Stepping(self.inner, plan, seed)
        for _ in stepping:
            pass
        return stepping.layout


def speed(dataset: str = "seen", n: int = 20, seeds: int = 1, solvers=SPEED_SOLVERS
          ) -> dict[str, dict[str, list[float]]]:
    """Wall and CPU seconds per object (solve time / plan objects) of each solver on each (plan, seed); the
    solvers take turns plan by plan, so that a change of machine load hits them alike. One warm-up solve
    each (weights, torch_geometric, the type embeddings and the priors load once per process) is not timed.
    CPU time (this process) is less sensitive than wall time to other processes sharing the cores."""
    import torch
    torch.set_num_threads(1)
    plans = [r.plan for r in pick_records(dataset, n)]
    instances = {name: _Stepped(name.removesuffix(STEPPED)) if name.endswith(STEPPED) else get_solver(name)
                 for name in solvers}
    for s in instances.values():
        s.solve(plans[0], seed=0)
    out: dict[str, dict[str, list[float]]] = {name: {"wall": [], "cpu": []} for name in solvers}
    for seed in range(seeds):
        for plan in plans:
            for name, s in instances.items():
                k = max(len(plan.objects), 1)
                t, c = time.perf_counter(), time.process_time()
                s.solve(plan, seed=seed)
                out[name]["cpu"].append((time.process_time() - c) / k)
                out[name]["wall"].append((time.perf_counter() - t) / k)
    return out


def speed_table(res: dict[str, dict[str, list[float]]], ref: str = "dfs") -> str:
    lines = [f"| solver | wall p50 | wall p90 | wall mean | CPU p50 | CPU p90 | wall p50 / {ref} | CPU p50 / {ref} |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    med = {name: {k: float(np.median(v)) for k, v in r.items()} for name, r in res.items()}
    for name, r in res.items():
        wall, cpu = 1000 * np.asarray(r["wall"]), 1000 * np.asarray(r["cpu"])
        rel = [f"{med[name][k] / med[ref][k]:.2f}" if ref in med else "n/a" for k in ("wall", "cpu")]
        lines.append(f"| {name} | {np.median(wall):.1f} | {np.percentile(wall, 90):.1f} | {wall.mean():.1f} | "
                     f"{np.median(cpu):.1f} | {np.percentile(cpu, 90):.1f} | {rel[0]} | {rel[1]} |")
    return "\n".join(lines) + "\n\n(ms per object: solve time / objects of the plan, over plans x seeds)"


if __name__ == "__main__":  # python -m app.bench.plan2place --speed [--n 20] [--seeds 5]
    import argparse
    import os
    ap = argparse.ArgumentParser()
    ap.add_argument("--speed", action="store_true", required=True)
    ap.add_argument("--dataset", default="seen")
    ap.add_argument("--n", type=int, default=20)
    # five, as the placement bench: DFS's time depends on the seed (on `dense` 4.2 ms p50 at seeds 0 and 1, 1.5-1.8 ms
    # at seeds 2-4; speed/five-seeds.txt)
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--solvers", default=",".join(SPEED_SOLVERS))
    a = ap.parse_args()
    with open("/proc/loadavg") as fh:
        load0 = fh.read().split()[:3]
    res = speed(a.dataset, a.n, a.seeds, [s for s in a.solvers.split(",") if s])
    with open("/proc/loadavg") as fh:
        load1 = fh.read().split()[:3]
    print(f"PTO on {a.n} `{a.dataset}` plans x {a.seeds} seed(s), one process, solvers in turn per plan, "
          f"{os.cpu_count()} CPUs, torch threads 1; loadavg before {' '.join(load0)}, after {' '.join(load1)}\n")
    print(speed_table(res))
