"""Batch throughput (`h3ds bench batch`): scenes per second of `h3ds batch generate` on local processes and on
a local Ray, 1 and 2 workers, on ALFRED valid_unseen instructions (picked as `h3ds bench generate` picks them,
200 unless --n says otherwise), and Ray's overhead per scene against local processes with as many workers,
measured in the same run.

Each run writes the same batch into a fresh folder. Its time is the batch's wall time, worker start-up and
each worker's pipeline warm-up included; starting Ray itself (`ray.init`, once per cluster) is reported
apart. Per worker count the runs go local, Ray, Ray, local and each configuration's time is the mean of its
two runs, so that a change in the load of a shared machine during the bench cancels out of the ratio.
Every scene's figures must come out identical in all runs, else the bench fails.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path

from app.batch.executors import LocalProcesses, RayExecutor
from app.batch.scenes import RESULTS, figures_of, run_batch
from app.bench.generate import pick_instructions

RESULTS_DIR = Path(__file__).resolve().parent / "results"
DEFAULT_N = 200  # the figure; `--n` (shared default 30, for `bench generate`) overrides it when given
ORDER = ("local", "ray", "ray", "local")  # per worker count (ABBA)


@dataclass
class Run:
    executor: str
    workers: int
    start_s: float  # building the executor (ray.init for Ray; local workers start inside the batch)
    batch_s: float
    scenes: int
    failed: int
    errors: list[str]

    @property
    def scenes_per_s(self) -> float:
        return self.scenes / self.batch_s


def write_input(path: Path, n: int) -> Path:
    """n ALFRED instructions as batch lines (seed = line index, dfs)."""
    lines = [json.dumps({"instruction": ins, "room_type": room, "seed": i, "solver": "dfs"})
             for i, (ins, room) in enumerate(pick_instructions(n))]
    path.write_text("\n".join(lines) + "\n")
    return path


def run_once(source: Path, out: Path, executor: str, workers: int) -> tuple[Run, list[dict]]:
    """The batch on one executor into a fresh folder: its timings and the scenes' figures."""
    t0 = time.perf_counter()
    ex = LocalProcesses(workers) if executor == "local" else RayExecutor(workers)
    t1 = time.perf_counter()
    with ex:
        summary = run_batch(source, out, ex, parser="rules", progress=False)
    t2 = time.perf_counter()
    rows = [json.loads(line) for line in (out / RESULTS).read_text().splitlines()]
    run = Run(ex.name, workers, t1 - t0, t2 - t1, summary.done, summary.failed, summary.errors)
    return run, [figures_of(r) for r in rows]


def mean_s(runs: list[Run], executor: str, workers: int, with_start: bool = False) -> float:
    times = [r.batch_s + with_start * r.start_s for r in runs if r.executor == executor and r.workers == workers]
    return sum(times) / len(times)


def report(runs: list[Run], n: int, identical: bool, loads: tuple[float, float]) -> list[str]:
    first = runs[0]
    lines = [f"batch generate on {n} ALFRED valid_unseen instructions, dfs placer: {first.scenes} scenes, "
             f"{first.failed} failed line(s); {os.cpu_count()} CPUs, load average {loads[0]:.1f} before the "
             f"bench, {loads[1]:.1f} after",
             *(f"  failed: {e}" for e in first.errors),
             f"  {'executor':<16} {'workers':>7} {'batch s (runs)':>20} {'scenes/s':>9} {'ms/scene':>9} {'vs local':>9}"]
    for workers in sorted({r.workers for r in runs}):
        local = mean_s(runs, LocalProcesses.name, workers)
        for executor in (LocalProcesses.name, RayExecutor.name):
            mean = mean_s(runs, executor, workers)
            each = " ".join(f"{r.batch_s:.1f}" for r in runs if r.executor == executor and r.workers == workers)
            lines.append(f"  {executor:<16} {workers:>7} {mean:>7.1f} ({each:>11}) {first.scenes / mean:>9.2f} "
                         f"{1000 * mean / first.scenes:>9.1f} {mean / local:>8.2f}x")
        extra_ms = 1000 * (mean_s(runs, RayExecutor.name, workers) - local) / first.scenes
        with_start_ms = 1000 * (mean_s(runs, RayExecutor.name, workers, with_start=True) - local) / first.scenes
        lines.append(f"  Ray overhead with {workers} worker(s): {extra_ms:+.1f} ms per scene "
                     f"({with_start_ms:+.1f} ms counting ray.init)")
    starts = sorted(r.start_s for r in runs if r.executor == RayExecutor.name)
    lines.append(f"  starting a local Ray (ray.init, which also starts its idle workers; not in the batch times): "
                 f"{starts[0]:.1f}-{starts[-1]:.1f} s")
    lines.append(f"  the scenes' figures are identical in the {len(runs)} runs: {'yes' if identical else 'NO'}")
    return lines


def main(args) -> int:
    n = DEFAULT_N if args.n == 30 else args.n
    load_before = os.getloadavg()[0]
    runs, outputs = [], []
    with tempfile.TemporaryDirectory(prefix="h3ds-bench-batch-") as tmp:
        source = write_input(Path(tmp) / "in.jsonl", n)
        for workers in (1, 2):
            for i, executor in enumerate(ORDER):
                out = Path(tmp) / f"{executor}-{workers}-{i}"
                run, rows = run_once(source, out, executor, workers)
                shutil.rmtree(out)
                runs.append(run)
                outputs.append(rows)
    identical = all(rows == outputs[0] for rows in outputs)
    loads = (load_before, os.getloadavg()[0])
    lines = report(runs, n, identical, loads)
    print("\n".join(lines))
    RESULTS_DIR.mkdir(exist_ok=True)
    (RESULTS_DIR / "batch.txt").write_text("\n".join(lines) + "\n")
    (RESULTS_DIR / "batch.json").write_text(json.dumps(
        {"n": n, "load_average_before_after": loads, "identical": identical,
         "runs": [{**asdict(r), "scenes_per_s": r.scenes_per_s} for r in runs]}, indent=1) + "\n")
    return 0 if identical else 1
