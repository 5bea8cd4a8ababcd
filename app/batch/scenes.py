"""`h3ds batch generate`: the pipeline on every line of a JSONL file, resumable, each scene kept once.

Output directory:

    OUT/scenes/<key>/   task_graph.json plan.json layout.json house.json scene.glb (as `h3ds generate`)
                        DONE.json: written last; the line's spec, each file's size and sha256, the row
    OUT/results.jsonl   one row per input line, in input order (loads with `datasets`)

A scene is written into `OUT/scenes/.tmp-<key>-...` and renamed into place with its marker inside, so
a worker or driver killed at any moment leaves either a finished scene or a temporary folder that the
next run deletes. A re-run skips the lines whose scene is complete on disk for the same spec
(instruction, room type, seed, solver, parser) and runs the rest again, failed lines included.
With `studio` (--studio) every scene also goes into the studio's database: see app/batch/studio.py.
"""

from __future__ import annotations

import fcntl
import hashlib
import json
import os
import re
import shutil
import socket
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path

from pydantic import BaseModel, ConfigDict, ValidationError, field_validator

from app.batch.executors import Done, Executor
from app.batch.studio import store_scene, stored_names, studio_name
from models.placement.base import DEFAULT_SOLVER, SOLVERS, UnknownSolver
from models.world.rooms import requested_room_type

MARKER = "DONE.json"
RESULTS = "results.jsonl"
SCENES = "scenes"
KEY = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]{0,99}$")
METRICS = ("cnt", "sr", "nav", "key_nav", "oob", "collisions", "constraint_satisfaction", "energy")
TIMINGS = ("generate_s", "place_s", "metrics_s", "write_s", "total_s")


class BatchError(ValueError):
    """A batch that cannot start (unreadable input, output folder in use); the CLI shows it as one line."""


class SceneSpec(BaseModel):
    """One input line. `id` names the scene's folder (default: `line-<n>`)."""

    model_config = ConfigDict(extra="forbid")

    id: str | None = None
    instruction: str
    room_type: str
    seed: int = 0
    solver: str = DEFAULT_SOLVER

    @field_validator("room_type")
    @classmethod
    def _known_room_type(cls, room_type: str) -> str:
        requested_room_type(room_type)  # refused here, before a worker spends time on the line
        return room_type

    @field_validator("solver")
    @classmethod
    def _known_solver(cls, solver: str) -> str:
        if solver.strip().lower() not in SOLVERS:
            raise UnknownSolver(solver)
        return solver


@dataclass(frozen=True)
class SceneTask:
    """What a worker needs for one scene (picklable)."""

    key: str
    line: int
    spec: SceneSpec
    out: str  # the batch's output folder, absolute (shared by every worker on a cluster)
    parser: str | None = None
    studio: str | None = None  # with --studio: the studio's database URL (app/batch/studio.py)

    def digest(self) -> str:
        fields = {**self.spec.model_dump(exclude={"id"}), "parser": self.parser}
        return hashlib.sha256(json.dumps(fields, sort_keys=True).encode()).hexdigest()


def row_of(task: SceneTask | None, line: int, key: str | None, error: str | None = None, **figures) -> dict:
    """A results row; every row has every column (None where a failed line has no figure) and only scalar
    values (`unplaced_ids` is space-separated), so the table loads as one dataset whatever the mix."""
    spec = task.spec if task else None
    row = {"key": key, "line": line, "instruction": spec.instruction if spec else None,
           "room_type": spec.room_type if spec else None, "seed": spec.seed if spec else None,
           "solver": spec.solver if spec else None, "status": "error" if error else "ok", "error": error,
           "dir": None, "n_objects": None, "placed": None, "unplaced": None, "unplaced_ids": None,
           **{m: None for m in METRICS}, **{t: None for t in TIMINGS}, "worker": None}
    row.update(figures)
    return row


def figures_of(row: dict) -> dict:
    """A results row without what depends on the clock or the worker: equal for the same line on any executor."""
    return {k: v for k, v in row.items() if k not in TIMINGS and k != "worker"}


# ---------------------------------------------------------------- the input


def read_tasks(path: Path, out: Path, parser: str | None = None,
               studio: str | None = None) -> tuple[list[SceneTask], list[dict]]:
    """The input's lines as tasks, and a results row with the error for each line that is not one."""
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise BatchError(f"{path}: cannot read the batch ({e})") from e
    tasks, bad, keys = [], [], set()
    for n, text in enumerate(lines, start=1):
        if not text.strip():
            continue
        key = None
        try:
            data = json.loads(text)
            if not isinstance(data, dict):
                raise ValueError(f"a line must be a JSON object, not {type(data).__name__}")
            spec = SceneSpec.model_validate(data)
            key = spec.id if spec.id is not None else f"line-{n:06d}"
            if not KEY.match(key):
                raise ValueError(f"id {key!r} cannot name a folder (letters, digits, '.', '_', '-'; at most 100)")
            if key in keys:
                raise ValueError(f"id {key!r} is used by an earlier line")
        except ValidationError as e:
            first = e.errors()[0]
            bad.append(row_of(None, n, key, f"line {n}: {'.'.join(map(str, first['loc']))}: {first['msg']}"))
            continue
        except json.JSONDecodeError as e:
            bad.append(row_of(None, n, key, f"line {n}: not a JSON object ({e.msg} at column {e.colno})"))
            continue
        except ValueError as e:
            bad.append(row_of(None, n, key, f"line {n}: {e}"))
            continue
        keys.add(key)
        tasks.append(SceneTask(key, n, spec, str(out.resolve()), parser, studio))
    return tasks, bad


# ---------------------------------------------------------------- one scene (runs in a worker)

_pipelines: dict = {}  # one Pipeline per parser per worker process, kept warm across tasks


def _pipeline(parser: str | None):
    if parser not in _pipelines:
        from app.pipeline import Pipeline
        from models.language.combined import make_parser
        _pipelines[parser] = Pipeline(parser=make_parser(parser) if parser else None)
    return _pipelines[parser]


def _file_digest(path: Path) -> dict:
    data = path.read_bytes()
    return {"bytes": len(data), "sha256": hashlib.sha256(data).hexdigest()}


def run_scene(task: SceneTask) -> dict:
    """Generate one scene and publish it atomically; return its results row. Errors propagate: the
    executor records them."""
    from app.pipeline import write_generation
    from models.energy.exact import layout_energy
    from models.metrics import scene_metrics
    from models.placement import PlacementProblem

    t0 = time.perf_counter()
    gen = _pipeline(task.parser).generate(task.spec.instruction, task.spec.room_type, seed=task.spec.seed,
                                          solver=task.spec.solver)
    t1 = time.perf_counter()
    problem = PlacementProblem.from_plan(gen.plan)
    metrics = scene_metrics(gen.plan, gen.layout, problem).as_dict()
    energy = layout_energy(gen.plan, gen.layout.placements, problem).total
    t2 = time.perf_counter()

    scenes = Path(task.out) / SCENES
    tmp = scenes / f".tmp-{task.key}-{uuid.uuid4().hex[:12]}"
    paths = write_generation(gen, tmp)
    t3 = time.perf_counter()
    row = row_of(task, task.line, task.key, dir=f"{SCENES}/{task.key}", n_objects=len(gen.plan.objects),
                 placed=len(gen.layout.placements), unplaced=len(gen.layout.unplaced),
                 unplaced_ids=" ".join(u.id for u in gen.layout.unplaced),
                 **{m: metrics[m] for m in METRICS if m != "energy"}, energy=energy,
                 generate_s=t1 - t0, place_s=gen.layout.timing.total_s, metrics_s=t2 - t1, write_s=t3 - t2,
                 total_s=t3 - t0, worker=f"{socket.gethostname()}:{os.getpid()}")
    marker = {"spec": task.spec.model_dump(), "parser": task.parser, "digest": task.digest(),
              "files": {p.name: _file_digest(p) for p in paths}, "row": row}
    (tmp / MARKER).write_text(json.dumps(marker, indent=1) + "\n")
    if task.studio:  # before publishing: a scene complete on disk is always in the database too
        store_scene(task.studio, studio_name(scenes.parent.name, task.key, task.digest()), gen, task.spec.seed,
                    task.spec.solver)
    publish(tmp, scenes / task.key, task.digest())
    return row


def publish(tmp: Path, final: Path, digest: str) -> None:
    """Rename a finished temporary folder into place. If the place is taken by the same finished scene
    (a retried task whose first attempt got there), keep that one; if by another spec's scene (the line
    changed), replace it."""
    try:
        os.rename(tmp, final)
        return
    except OSError:
        if not final.exists():
            raise
    if complete(final, digest):
        shutil.rmtree(tmp, ignore_errors=True)
        return
    old = final.with_name(f".old-{final.name}-{uuid.uuid4().hex[:12]}")
    os.rename(final, old)
    os.rename(tmp, final)
    shutil.rmtree(old, ignore_errors=True)


def complete(folder: Path, digest: str, verify: bool = False) -> dict | None:
    """The marker of a finished scene for this spec, or None. Sizes are always checked; `verify` also
    re-hashes every file."""
    try:
        marker = json.loads((folder / MARKER).read_text())
    except (OSError, json.JSONDecodeError):
        return None
    if marker.get("digest") != digest:
        return None
    for name, want in marker.get("files", {}).items():
        path = folder / name
        try:
            if path.stat().st_size != want["bytes"]:
                return None
        except OSError:
            return None
        if verify and _file_digest(path)["sha256"] != want["sha256"]:
            return None
    return marker


# ---------------------------------------------------------------- the driver


@dataclass
class Summary:
    total: int = 0
    skipped: int = 0  # complete on disk before this run
    done: int = 0
    failed: int = 0
    seconds: float = 0.0
    errors: list[str] = field(default_factory=list)


class _Lock:
    """One driver per output folder (an exclusive lock on OUT/.batch.lock, released when the driver ends,
    however it ends)."""

    def __init__(self, out: Path):
        self.file = open(out / ".batch.lock", "w")
        try:
            fcntl.flock(self.file, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError as e:
            self.file.close()
            raise BatchError(f"{out}: another batch is writing to this folder") from e

    def release(self) -> None:
        self.file.close()


def _clean_temporaries(scenes: Path) -> int:
    """Delete what killed workers left half-written (only ever `.tmp-*` / `.old-*`, never a scene)."""
    stale = [p for p in scenes.iterdir() if p.name.startswith((".tmp-", ".old-"))]
    for p in stale:
        shutil.rmtree(p, ignore_errors=True)
    return len(stale)


def write_results(out: Path, rows: dict[int, dict]) -> Path:
    """results.jsonl in input-line order, replaced atomically."""
    path = out / RESULTS
    tmp = out / f".{RESULTS}.tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        for line in sorted(rows):
            f.write(json.dumps(rows[line]) + "\n")
    os.replace(tmp, path)
    return path


def run_batch(source: Path, out: Path, executor: Executor, parser: str | None = None, progress: bool = True,
              studio: str | None = None) -> Summary:
    """Every line of `source` into `out`; see the module docstring. `studio`: a database URL to store every
    scene in as well (a scene complete on disk but missing there is made again)."""
    tasks, bad = read_tasks(source, out, parser, studio)
    out.mkdir(parents=True, exist_ok=True)
    lock = _Lock(out)
    try:
        scenes = out / SCENES
        scenes.mkdir(exist_ok=True)
        _clean_temporaries(scenes)
        rows = {r["line"]: r for r in bad}
        todo = []
        in_studio = stored_names(studio, out.resolve().name) if studio else set()
        for t in tasks:
            marker = complete(scenes / t.key, t.digest())
            if marker is None or (studio and studio_name(out.resolve().name, t.key, t.digest()) not in in_studio):
                todo.append(t)
            else:
                rows[t.line] = marker["row"]
        summary = Summary(total=len(tasks) + len(bad), skipped=len(tasks) - len(todo), failed=len(bad),
                          errors=[r["error"] for r in bad])
        start = time.perf_counter()
        bar = _bar(summary, progress)
        try:
            for done in executor.run(run_scene, todo):
                row = _row_of(done, todo)
                rows[row["line"]] = row
                if row["status"] == "ok":
                    summary.done += 1
                else:
                    summary.failed += 1
                    summary.errors.append(f"line {row['line']} ({row['key']}): {row['error']}")
                bar.set_postfix(done=summary.done + summary.skipped, failed=summary.failed, refresh=False)
                bar.update(1)
        finally:
            bar.close()
            summary.seconds = time.perf_counter() - start
            write_results(out, rows)
        return summary
    finally:
        lock.release()


def _row_of(done: Done, todo: list[SceneTask]) -> dict:
    task = todo[done.index]
    return done.value if done.error is None else row_of(task, task.line, task.key, done.error)


def _bar(summary: Summary, show: bool):
    from tqdm import tqdm
    return tqdm(total=summary.total, initial=summary.skipped + len(summary.errors), unit="scene",
                desc="scenes", disable=not show, dynamic_ncols=True, smoothing=0.05,
                postfix={"done": summary.skipped, "failed": summary.failed})
