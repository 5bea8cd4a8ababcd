"""Batch generation: bad lines recorded, resumption, the same outputs in process, on local processes and on a
local Ray, a killed worker and a killed driver on both (every scene once on disk and in the studio's database),
the progress bar, Ray imported only when asked for."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import psutil
import pytest

from app.batch.executors import InProcess, LocalProcesses, RayExecutor, guarded
from app.batch.scenes import MARKER, SCENES, BatchError, complete, read_tasks, run_batch
from app.batch.studio import studio_name
from app.pipeline import generation_of
from batch_support import figures, results, scene_files, write_lines
from studio_db.store import Store

H3DS = [sys.executable, "-m", "app.cli"]
N = 16  # lines of the shared batch: enough that the kill tests' drivers die with most of it still to do


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    """A batch of N lines and its reference output, generated in this process."""
    folder = tmp_path_factory.mktemp("batch")
    source = write_lines(folder / "in.jsonl", N)
    run_batch(source, folder / "reference", InProcess(), progress=False)
    return SimpleNamespace(source=source, reference=folder / "reference")


@pytest.fixture(scope="module")
def local_ray():
    """One local Ray with 2 CPUs for the module (starting one takes seconds); its address, for drivers that
    join it as they would join a cluster."""
    import ray
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    yield ray.get_runtime_context().gcs_address
    ray.shutdown()


def test_bad_lines_are_recorded_and_the_batch_goes_on(tmp_path):
    source = write_lines(tmp_path / "in.jsonl", 2, extra=[
        "not json",
        json.dumps({"instruction": "Put a chilled bread on the counter", "room_type": "spaceship"}),
        json.dumps({"instruction": "Put a chilled bread on the counter", "room_type": "kitchen", "solver": "nope"}),
        json.dumps({"instruction": "Put a chilled bread on the counter"}),
        json.dumps({"id": "../escape", "instruction": "Put a chilled bread on the counter", "room_type": "kitchen"}),
        json.dumps({"instruction": "Put a chilled bread on the counter", "room_type": "kitchen", "sead": 3}),
        json.dumps({"instruction": "Do a task with both hands", "room_type": "kitchen"})])  # fails in the pipeline
    out = tmp_path / "out"
    summary = run_batch(source, out, InProcess(), progress=False)
    assert (summary.total, summary.done, summary.failed) == (9, 2, 7)
    rows = results(out)
    assert [r["line"] for r in rows] == list(range(1, 10))
    assert [r["status"] for r in rows] == ["ok", "ok"] + ["error"] * 7
    errors = [r["error"] for r in rows[2:]]
    assert "line 3: not a JSON object" in errors[0] and "line 4: room_type" in errors[1] and "spaceship" in errors[1]
    assert "line 5: solver" in errors[2] and "unknown solver 'nope'" in errors[2]
    assert "room_type" in errors[3] and "cannot name a folder" in errors[4] and "sead" in errors[5]
    assert errors[6].startswith("no object to pick up") and rows[8]["key"] == "line-000009"  # by its message alone
    assert sorted(p.name for p in (out / SCENES).iterdir()) == ["line-000001", "line-000002"]
    ok = rows[0]
    assert ok["placed"] + ok["unplaced"] == ok["n_objects"] > 0 and ok["energy"] is not None
    assert ok["generate_s"] > 0 and ok["place_s"] > 0 and ok["cnt"] == ok["placed"] / ok["n_objects"]

    import datasets
    table = datasets.load_dataset("json", data_files=str(out / "results.jsonl"), split="train")
    assert table.num_rows == 9 and table["status"].count("error") == 7


def test_an_input_error_reads_as_its_message_a_fault_of_ours_says_where():
    from models.world import normalise_room_type

    ok, error = guarded(normalise_room_type, "moon")
    assert not ok and error.startswith("unknown room type 'moon'") and "(at " not in error
    ok, error = guarded(lambda items: items[1], [])
    assert not ok and error.startswith("IndexError: list index out of range (at test_batch.py:")


def test_input_that_cannot_start_a_batch_is_refused(tmp_path):
    with pytest.raises(BatchError, match="cannot read"):
        run_batch(tmp_path / "missing.jsonl", tmp_path / "out", InProcess(), progress=False)
    assert not (tmp_path / "out").exists()
    source = write_lines(tmp_path / "in.jsonl", 1, extra=[json.dumps({"id": "line-000001", "instruction": "x",
                                                                     "room_type": "kitchen"})])
    tasks, bad = read_tasks(source, tmp_path)
    assert len(tasks) == 1 and "used by an earlier line" in bad[0]["error"]
    proc = subprocess.run(H3DS + ["batch", "generate", str(tmp_path / "missing.jsonl"), "--out", str(tmp_path / "o")],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "missing.jsonl" in proc.stderr and "Traceback" not in proc.stderr


def test_a_rerun_skips_finished_scenes_and_redoes_changed_broken_and_failed_ones(tmp_path):
    source = write_lines(tmp_path / "in.jsonl", 4, extra=[json.dumps({"instruction": "x", "room_type": "kitchen"})])
    out = tmp_path / "out"
    first = run_batch(source, out, InProcess(), progress=False)
    assert (first.done, first.failed) == (4, 1)
    scenes = out / SCENES
    kept = (scenes / "line-000001" / MARKER).stat().st_mtime_ns
    (scenes / "line-000002" / "scene.glb").write_bytes(b"half")  # damaged after the fact
    (scenes / ".tmp-line-000003-dead").mkdir()  # what a killed worker leaves
    lines = source.read_text().splitlines()
    lines[3] = lines[3].replace('"seed": 3', '"seed": 30')  # the line changed
    source.write_text("\n".join(lines) + "\n")

    second = run_batch(source, out, InProcess(), progress=False)
    assert (second.skipped, second.done, second.failed) == (2, 2, 1)
    assert (scenes / "line-000001" / MARKER).stat().st_mtime_ns == kept
    assert not (scenes / ".tmp-line-000003-dead").exists()
    assert json.loads((scenes / "line-000004" / "layout.json").read_text())["seed"] == 30
    rows = results(out)
    assert [r["status"] for r in rows] == ["ok"] * 4 + ["error"] and rows[3]["seed"] == 30
    tasks, _ = read_tasks(source, out)
    assert [bool(complete(scenes / t.key, t.digest(), verify=True)) for t in tasks] == [True] * 4 + [False]


def test_local_processes_and_a_local_ray_give_the_same_outputs(batch, local_ray, tmp_path):
    with LocalProcesses(2) as ex:
        run_batch(batch.source, tmp_path / "local", ex, progress=False)
    with RayExecutor(2) as ex:
        run_batch(batch.source, tmp_path / "ray", ex, progress=False)
    for out in (tmp_path / "local", tmp_path / "ray"):
        assert scene_files(out) == scene_files(batch.reference)
        assert figures(out) == figures(batch.reference)
    assert len({r["worker"] for r in results(tmp_path / "local")}) == 2  # (Ray may reuse one worker for all)


def die_once(flag: str) -> int:
    """Kill the calling process the first time (as the OOM killer would), succeed after."""
    if not os.path.exists(flag):
        Path(flag).touch()
        os._exit(9)
    return os.getpid()


def always_die(_item) -> None:
    os._exit(9)


def test_a_dead_worker_is_replaced_and_its_item_retried_then_given_up(tmp_path):
    with LocalProcesses(2, max_retries=1) as ex:
        done = sorted(ex.run(die_once, [str(tmp_path / "a"), str(tmp_path / "b"), str(tmp_path / "c")]),
                      key=lambda d: d.index)
        assert [d.error for d in done] == [None] * 3 and all(d.value > 0 for d in done)
        gave_up = list(ex.run(always_die, [0]))
        assert "died 2 times" in gave_up[0].error


def _local_workers(driver: subprocess.Popen) -> list[psutil.Process]:
    return [c for c in psutil.Process(driver.pid).children() if "spawn_main" in " ".join(c.cmdline())]


def _ray_workers(_driver: subprocess.Popen) -> list[psutil.Process]:
    """The Ray workers running a scene now (the raylet's children, titled by the task they run)."""
    return [p for p in psutil.process_iter(["cmdline"]) if (p.info["cmdline"] or [""])[0] == "ray::guarded"]


def _finished(out: Path) -> int:
    folder = out / SCENES
    return sum((p / MARKER).exists() for p in folder.iterdir() if not p.name.startswith(".")) if folder.exists() else 0


def _wait_for(condition, timeout: float = 60.0):
    end = time.monotonic() + timeout
    while not (value := condition()):
        assert time.monotonic() < end, "timed out"
        time.sleep(0.02)
    return value


@pytest.mark.parametrize("on", ["local", "ray"])
def test_killed_worker_and_killed_driver_leave_every_scene_exactly_once_and_intact(on, batch, tmp_path, request):
    out = tmp_path / "out"
    where = ["--workers", "2"] if on == "local" else ["--ray-address", request.getfixturevalue("local_ray")]
    workers_of = _local_workers if on == "local" else _ray_workers
    cmd = H3DS + ["batch", "generate", str(batch.source), "--out", str(out), "--no-progress", "--studio", *where]
    env = {**os.environ, "DATABASE_URL": f"sqlite:///{tmp_path / 'studio.db'}"}
    driver = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
    try:
        _wait_for(lambda: _finished(out) >= 1)
        workers = _wait_for(lambda: workers_of(driver))
        workers[0].send_signal(signal.SIGKILL)  # a worker dies in the middle of a scene
        at_kill = _finished(out)
        _wait_for(lambda: _finished(out) >= at_kill + 3)
        driver.send_signal(signal.SIGKILL)  # then the driver dies too
        driver.wait(timeout=30)
        assert _finished(out) < N, "the batch ended before the driver was killed: the test proved nothing"
    finally:
        if driver.poll() is None:
            driver.kill()
    restart = subprocess.run(cmd, capture_output=True, text=True, timeout=120, env=env)
    assert restart.returncode == 0, restart.stderr
    assert "already complete" in restart.stdout

    tasks, _ = read_tasks(batch.source, out)
    folders = sorted(p.name for p in (out / SCENES).iterdir())
    assert folders == sorted(t.key for t in tasks)  # exactly once, no leftovers
    assert all(complete(out / SCENES / t.key, t.digest(), verify=True) for t in tasks)
    rows = results(out)
    assert [r["line"] for r in rows] == list(range(1, N + 1)) and {r["status"] for r in rows} == {"ok"}
    assert scene_files(out) == scene_files(batch.reference)
    stored = [s["name"] for s in Store(env["DATABASE_URL"]).list_scenes()]
    assert sorted(stored) == sorted(studio_name("out", t.key, t.digest()) for t in tasks)


def test_studio_gets_each_scene_once_and_a_rerun_adds_only_the_missing_ones(tmp_path):
    url = f"sqlite:///{tmp_path / 'studio.db'}"
    source = write_lines(tmp_path / "in.jsonl", 2)
    run_batch(source, tmp_path / "a", InProcess(), progress=False)  # first without --studio
    assert run_batch(source, tmp_path / "a", InProcess(), progress=False, studio=url).done == 2
    again = run_batch(source, tmp_path / "a", InProcess(), progress=False, studio=url)
    assert (again.skipped, again.done) == (2, 0)
    store = Store(url)
    scenes = store.list_scenes()
    assert sorted(s["name"] for s in scenes) == [f"a/line-00000{i} ({t.digest()[:8]})"
                                                for i, t in enumerate(read_tasks(source, tmp_path)[0], start=1)]
    gen = generation_of(store.scene(scenes[0]["id"]))  # opens in the studio like a scene saved there
    assert gen.layout.placements and store.versions(scenes[0]["id"])[0]["solver"] == "dfs"


def test_the_progress_bar_shows_done_failed_rate_and_time_left(tmp_path, capsys):
    source = write_lines(tmp_path / "in.jsonl", 2, extra=["not json"])
    run_batch(source, tmp_path / "out", InProcess(), progress=True)
    bar = capsys.readouterr().err.split("\r")[-1]
    assert "3/3" in bar and "done=2" in bar and "failed=1" in bar and "scene/s" in bar and "<00:00" in bar


def test_ray_is_imported_only_when_asked_for():
    code = ("import sys, app.cli, app.batch.scenes, app.batch.executors as ex; ex.make_executor(1).close(); "
            "assert 'ray' not in sys.modules, 'ray imported'")
    subprocess.run([sys.executable, "-c", code], check=True, timeout=60)


def test_bench_placement_through_worker_processes_gives_the_same_rows(tmp_path):
    from app.bench.placement import main
    base = dict(dataset="unseen_b", solvers="dfs", n=2, seeds=2, budget=None)
    main(SimpleNamespace(**base, out=str(tmp_path / "a")))
    main(SimpleNamespace(**base, out=str(tmp_path / "b"), workers=2, ray=False, ray_address=None))
    clock = ("pto", "time_s")
    rows = [[{k: v for k, v in r.items() if k not in clock} for r in json.loads((tmp_path / d / "results.json").read_text())]
            for d in "ab"]
    assert rows[0] == rows[1] and len(rows[0]) == 4


def test_a_line_may_ask_for_its_room_type_to_be_inferred(tmp_path):
    source = tmp_path / "in.jsonl"
    source.write_text(json.dumps({"instruction": "Look at the book under the lamp", "room_type": "infer"}) + "\n")
    tasks, bad = read_tasks(source, tmp_path)
    assert len(tasks) == 1 and not bad
