"""Where batch work runs: one small interface, three implementations.

- `InProcess`: in the calling process, one item after another (the old behaviour of `h3ds data build`
  and `h3ds bench placement`, and a baseline for the benchmark).
- `LocalProcesses`: N worker processes started with `spawn` (no Ray needed; the default of
  `h3ds batch generate`). A worker that dies (killed, crashed) is replaced and its item retried.
- `RayExecutor`: Ray tasks, on a local Ray started here (`--ray`) or on a cluster (`--ray-address`,
  or `RAY_ADDRESS`). Ray retries a task whose worker died. `ray` is imported only here, lazily.

Every executor takes a picklable module-level function and a list of items and yields `Done` in the
order items finish; an exception inside `fn` becomes `Done.error` and never stops the other items.
"""

from __future__ import annotations

import os
import traceback
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

from models.errors import InputError

MAX_RETRIES = 2  # extra attempts for an item whose worker process died under it (Ray's default is 3)


@dataclass(frozen=True)
class Done:
    """One finished item: its index in the submitted list and either its value or an error line."""

    index: int
    value: Any = None
    error: str | None = None


class Executor(Protocol):
    name: str
    workers: int

    def run(self, fn: Callable[[Any], Any], items: Sequence[Any]) -> Iterator[Done]:
        """Run `fn(item)` for every item; yield each result as it finishes (any order)."""

    def close(self) -> None:
        """Stop the workers this executor started."""


def describe(e: BaseException) -> str:
    """An exception as one line: a user's input error (models.errors) by its message alone, anything else by its
    type, message and the place in our code it came from."""
    if isinstance(e, InputError):
        return str(e)
    frames = [f for f in traceback.extract_tb(e.__traceback__) if "/site-packages/" not in f.filename]
    where = f" (at {os.path.basename(frames[-1].filename)}:{frames[-1].lineno})" if frames else ""
    return f"{type(e).__name__}: {e}{where}"


def guarded(fn: Callable[[Any], Any], item: Any) -> tuple[bool, Any]:
    """`fn(item)` as (True, value) or (False, error line), described where it happened, so that every
    executor reports the same text for the same error."""
    try:
        return True, fn(item)
    except Exception as e:  # one bad item never stops the batch
        return False, describe(e)


class _Closing:
    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class InProcess(_Closing):
    name = "in-process"
    workers = 1

    def run(self, fn, items):
        for i, item in enumerate(items):
            ok, value = guarded(fn, item)
            yield Done(i, value) if ok else Done(i, error=value)

    def close(self) -> None:
        pass


def _worker_main(conn) -> None:
    """A local worker: receive (index, fn, item), send back (index, ok, value or error), until told to stop
    or the driver is gone."""
    while True:
        try:
            msg = conn.recv()
        except (EOFError, OSError):
            return
        if msg is None:
            return
        index, fn, item = msg
        try:
            conn.send((index, *guarded(fn, item)))
        except (BrokenPipeError, OSError):
            return


@dataclass
class _Worker:
    process: Any
    conn: Any
    task: tuple[int, Any] | None = None


class LocalProcesses(_Closing):
    """N `spawn` processes, one item at a time each; a dead worker is replaced and its item retried
    (at most MAX_RETRIES more times, then the item is reported as an error)."""

    name = "local processes"

    def __init__(self, workers: int | None = None, max_retries: int = MAX_RETRIES):
        import multiprocessing

        self.workers = max(1, workers or os.cpu_count() or 1)
        self.max_retries = max_retries
        self._ctx = multiprocessing.get_context("spawn")
        self._pool: list[_Worker] = []

    def _spawn(self) -> _Worker:
        parent, child = self._ctx.Pipe()
        process = self._ctx.Process(target=_worker_main, args=(child,), daemon=True, name="h3ds-worker")
        process.start()
        child.close()
        return _Worker(process, parent)

    def run(self, fn, items):
        from multiprocessing.connection import wait

        queue = deque(enumerate(items))
        deaths: dict[int, int] = {}
        while len(self._pool) < min(self.workers, len(queue)):
            self._pool.append(self._spawn())
        while queue or any(w.task for w in self._pool):
            for w in self._pool:
                if w.task is None and queue:
                    w.task = queue.popleft()
                    w.conn.send((w.task[0], fn, w.task[1]))
            busy = [w for w in self._pool if w.task is not None]
            wait([w.conn for w in busy] + [w.process.sentinel for w in busy])
            for w in busy:
                reply = None
                if w.conn.poll():
                    try:
                        reply = w.conn.recv()
                    except (EOFError, OSError):
                        reply = None
                if reply is not None:
                    w.task = None
                    index, ok, value = reply
                    yield Done(index, value) if ok else Done(index, error=value)
                elif not w.process.is_alive():
                    index, item = w.task
                    deaths[index] = deaths.get(index, 0) + 1
                    self._replace(w)
                    if deaths[index] > self.max_retries:
                        yield Done(index, error=f"WorkerDied: the worker process died {deaths[index]} times on "
                                                f"this item (last exit code {w.process.exitcode})")
                    else:
                        queue.appendleft((index, item))

    def _replace(self, dead: _Worker) -> None:
        dead.conn.close()
        self._pool[self._pool.index(dead)] = self._spawn()

    def close(self) -> None:
        for w in self._pool:
            try:
                w.conn.send(None)
            except (BrokenPipeError, OSError):
                pass
        for w in self._pool:
            w.process.join(timeout=5)
            if w.process.is_alive():
                w.process.kill()
                w.process.join()
            w.conn.close()
        self._pool = []


class RayExecutor(_Closing):
    """Ray tasks (1 CPU each). Without an address a local Ray is started with `workers` CPUs and shut down
    on close; with one (or RAY_ADDRESS) the cluster is joined and `workers` defaults to its CPUs. At most
    2 x workers tasks are in flight, so a batch of millions does not sit in Ray's object store at once."""

    name = "ray"

    def __init__(self, workers: int | None = None, address: str | None = None, max_retries: int = MAX_RETRIES):
        import ray

        self._ray = ray
        self.address = address or os.environ.get("RAY_ADDRESS") or None
        self._owns = not ray.is_initialized()
        if self._owns:
            if self.address:
                ray.init(address=self.address, log_to_driver=False)
            else:
                ray.init(num_cpus=max(1, workers or os.cpu_count() or 1), include_dashboard=False,
                         log_to_driver=False)
        self.workers = max(1, workers or int(ray.cluster_resources().get("CPU", 1)))
        self.max_retries = max_retries

    def run(self, fn, items):
        ray = self._ray
        task = ray.remote(num_cpus=1, max_retries=self.max_retries, retry_exceptions=False)(guarded)
        todo = iter(enumerate(items))
        pending: dict[Any, int] = {}

        def submit() -> None:
            for index, item in todo:
                pending[task.remote(fn, item)] = index
                if len(pending) >= 2 * self.workers:
                    return

        submit()
        while pending:
            ready, _ = ray.wait(list(pending), num_returns=1)
            for ref in ready:
                index = pending.pop(ref)
                try:
                    ok, value = ray.get(ref)
                except ray.exceptions.RayError as e:  # the worker died more than max_retries times, ...
                    yield Done(index, error=f"{type(e).__name__}: {str(e).strip().splitlines()[0]}")
                    continue
                yield Done(index, value) if ok else Done(index, error=value)
            submit()

    def close(self) -> None:
        if self._owns and self._ray.is_initialized():
            self._ray.shutdown()


def make_executor(workers: int | None = None, ray: bool = False, ray_address: str | None = None,
                  serial_default: bool = False) -> Executor:
    """The executor the command-line options ask for: Ray if --ray, --ray-address or RAY_ADDRESS says so,
    else local processes. `serial_default`: with neither --workers nor Ray, run in this process (the
    commands whose old behaviour that was)."""
    if ray or ray_address or os.environ.get("RAY_ADDRESS"):
        return RayExecutor(workers, ray_address)
    if serial_default and not workers:
        return InProcess()
    return LocalProcesses(workers)


def executor_from_args(args, serial_default: bool = False) -> Executor:
    """`make_executor` from argparse options (--workers, --ray, --ray-address); absent options are defaults."""
    return make_executor(getattr(args, "workers", None), getattr(args, "ray", False),
                         getattr(args, "ray_address", None), serial_default)
