"""Does the learning do something? Plan2Place checkpoints against the same network untrained and the
greedy placer, on the same plans in one run; also the ablation runs (each its own checkpoint).

    h3ds bench plan2place --dataset seen --n 40 --seeds 1 --runs models/weights/plan2place/plan2place.pt
    h3ds bench plan2place --runs runs/main,runs/noglobal,runs/nosff,runs/noaux,runs/concat,runs/h64

A run is a checkpoint file or a training folder (its checkpoint.pt). Figures: the exact energy of the
final layout (the RL objective; lower is better), the placement metrics x 100, PTO p50 per object.
"""

from __future__ import annotations

import statistics
import time
from pathlib import Path

import numpy as np

from app.bench.placement import pick_records, score
from models.placement import get_solver

METRICS = [("energy", "energy", 1), ("cnt", "CNT", 100), ("sr", "SR", 100), ("key_nav", "Key_NAV", 100),
           ("nav", "NAV", 100), ("constraint_satisfaction", "constraints", 100), ("realism", "realism", 100),
           ("collisions", "collisions", 1)]


def solver_for(run: str):
    import torch

    from models.placement.plan2place.solver import Plan2PlaceSolver, load_network
    path = Path(run)
    ckpt = path / "checkpoint.pt" if path.is_dir() else path
    state = torch.load(ckpt, weights_only=False)
    label = path.name if path.is_dir() else path.stem
    return Plan2PlaceSolver(load_network(state), name=f"{label} ({state['episode']} ep)")


def evaluate(solvers: list, plans: list, seeds: int) -> dict[str, list[dict]]:
    rows: dict[str, list[dict]] = {}
    for solver in solvers:
        for seed in range(seeds):
            for plan in plans:
                t = time.perf_counter()
                layout = solver.solve(plan, seed=seed)
                elapsed = time.perf_counter() - t
                rows.setdefault(solver.name, []).append({**score(plan, layout),
                                                         "pto_s": elapsed / max(len(plan.objects), 1)})
    return rows


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


def main(args) -> int:
    plans = [r.plan for r in pick_records(args.dataset, args.n)]
    runs = [r for r in (args.runs or "models/weights/plan2place/plan2place.pt").split(",") if r]
    solvers = [get_solver("greedy"), get_solver("plan2place_untrained")] + [solver_for(r) for r in runs]
    rows = evaluate(solvers, plans, args.seeds)
    text = (f"plan2place bench on {len(plans)} `{args.dataset}` plans x {args.seeds} seed(s); energy = exact "
            f"energy of the final layout (lower is better), metrics x 100\n\n{table(rows)}\n")
    print(text)
    if args.out:
        Path(args.out).mkdir(parents=True, exist_ok=True)
        (Path(args.out) / "plan2place.md").write_text(text)
    return 0
