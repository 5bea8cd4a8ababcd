"""`h3ds bench steps`: how soon an HTTP client sees Plan2Place at work through `POST /place/steps`, against waiting
for `POST /place`'s layout, over a real loopback server (uvicorn in its own thread) in one process.

Per plan (the placement bench's `--dataset` plans, `--n` of them, `--seeds` seeds each), in turn: `POST /place`
(the baseline: the time to the whole layout), then `POST /place/steps` with the default record (5 best
candidates) and with every candidate (a client's floor heat-map): the time to the first step line, to the
layout line, and the bytes sent. Prints a table and writes `results/place-steps.md`.
"""

from __future__ import annotations

import json
import os
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

RESULTS = Path(__file__).resolve().parent / "results"


def _serve(pipeline):
    import uvicorn

    from app.api import create_app
    from frontend.server import free_port
    from studio_db import Store
    store = Store(f"sqlite:///{tempfile.mkdtemp(prefix='h3ds-bench-steps-')}/studio.db")
    port = free_port("127.0.0.1", 18950)
    server = uvicorn.Server(uvicorn.Config(create_app(store, pipeline), host="127.0.0.1", port=port,
                                           log_level="warning"))
    threading.Thread(target=server.run, daemon=True).start()
    while not server.started:
        time.sleep(0.02)
    return server, f"http://127.0.0.1:{port}"


def _streamed(client, body: dict, top: int) -> tuple[float, float, int, int]:
    """(seconds to the first step line, seconds to the layout line, step lines, bytes) of one POST /place/steps."""
    start, first, size, steps = time.perf_counter(), None, 0, 0
    with client.stream("POST", "/place/steps", json=body, params={"top": top}) as r:
        r.raise_for_status()
        for line in r.iter_lines():
            if not line:
                continue
            size += len(line) + 1
            record = json.loads(line)
            if "error" in record:
                raise RuntimeError(record["error"])
            if "step" in record:
                steps += 1
                first = first if first is not None else time.perf_counter() - start
    return first, time.perf_counter() - start, steps, size


def main(args) -> int:
    import httpx

    from app.api import MAX_TOP
    from app.bench.placement import pick_records
    from app.pipeline import Pipeline
    from models.placement import DEFAULT_SOLVER
    from models.placement.stepping import TOP

    solver = (args.solvers or DEFAULT_SOLVER).split(",")[0]
    records = pick_records(args.dataset, args.n)
    server, url = _serve(Pipeline())
    rows: dict[str, list] = {"place": [], "first": [], "steps": [], "first_all": [], "steps_all": []}
    sizes: dict[str, list] = {"top": [], "all": []}
    with httpx.Client(base_url=url, timeout=600) as client:
        client.post("/place", json={"plan": json.loads(records[0].plan.model_dump_json()), "solver": solver})  # warm-up
        for record in records:
            plan = json.loads(record.plan.model_dump_json())
            for seed in range(args.seeds):
                body = {"plan": plan, "seed": seed, "solver": solver}
                start = time.perf_counter()
                client.post("/place", json=body).raise_for_status()
                rows["place"].append(time.perf_counter() - start)
                first, total, steps, size = _streamed(client, body, TOP)
                rows["first"].append(first)
                rows["steps"].append(total)
                sizes["top"].append(size / max(steps, 1))
                first, total, steps, size = _streamed(client, body, MAX_TOP)
                rows["first_all"].append(first)
                rows["steps_all"].append(total)
                sizes["all"].append(size / max(steps, 1))
    server.should_exit = True
    ms = {k: np.array(v) * 1000 for k, v in rows.items()}
    place = float(np.median(ms["place"]))
    runs = len(ms["place"])
    lines = [f"`POST /place/steps` against `POST /place`, solver `{solver}`, {len(records)} `{args.dataset}` plans x "
             f"{args.seeds} seeds ({runs} runs), real loopback HTTP (uvicorn), one process, {os.cpu_count()} CPUs; "
             f"loadavg {os.getloadavg()[0]:.2f}.", "",
             "| measure | p50 (ms) | p90 (ms) | p50 / `POST /place` |", "| --- | --- | --- | --- |"]
    names = {"place": "`POST /place`: the layout", "first": "steps (5 best candidates): first step",
             "steps": "steps (5 best candidates): the layout line", "first_all": "steps (every candidate): first step",
             "steps_all": "steps (every candidate): the layout line"}
    for key, name in names.items():
        p50, p90 = float(np.median(ms[key])), float(np.percentile(ms[key], 90))
        lines.append(f"| {name} | {p50:.1f} | {p90:.1f} | {p50 / place:.2f} |")
    lines += ["", f"Bytes per step line, median: {np.median(sizes['top']):.0f} (5 best candidates), "
                  f"{np.median(sizes['all']):.0f} (every candidate)."]
    text = "\n".join(lines)
    print(text)
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "place-steps.md").write_text(text + "\n")
    return 0
