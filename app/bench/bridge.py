"""`h3ds bench bridge`: glove events per second stored with acks over a real loopback websocket, and the
latency from an event's creation on the headset to its arrival in the studio's feedback panel model.

The headset is the headset simulator (a stand-in for the Quest app) in this process; the studio is the
API server (uvicorn, own thread) over a fresh SQLite file. Three runs: saturated (the headset keeps up to
WINDOW events unacked, as a buffering headset does), paced at 1,000 events/s (latency at the target rate)
and the baseline in the same process: the same events written straight to the store one transaction per
event (what the bridge would cost without batching, and without any network).
"""

from __future__ import annotations

import asyncio
import importlib.util
import json
import platform
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

RESULTS = Path(__file__).resolve().parent / "results"
ROOT = Path(__file__).resolve().parents[2]
WINDOW = 1000  # unacked events the headset lets fly before waiting


def _simulator():
    spec = importlib.util.spec_from_file_location("headset_sim", ROOT / "unity-bridge" / "simulator" / "headset_sim.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.HeadsetSimulator


class _Timed:
    """Listener: puts each stored event into a FeedbackView (the panel's model) and times its arrival."""

    def __init__(self):
        from frontend.headset_panel import FeedbackView
        self.view, self.latency_ms = FeedbackView(), []

    def __call__(self, kind, payload):
        if kind == "feedback":
            self.view.add(payload)
            now = time.time()
            self.latency_ms.extend((now - m["ts"]) * 1000 for m in payload)


async def _stream(sim, push_id: str, n: int, rate: float | None) -> float:
    start = time.perf_counter()
    for i in range(n):
        if rate is not None:
            wait = start + i / rate - time.perf_counter()
            if wait > 0:
                await asyncio.sleep(wait)
        while len(sim.outbox) >= WINDOW:
            await asyncio.sleep(0.001)
        await sim.glove_event(push_id, i * 0.001, "Bread|1", "Bread", ("hover", "select")[i % 2], "right",
                              ["thumb", "index"], "cold", 55, [0.0, 0.35, 1.0])
    if not await sim.wait_acked(120):
        raise RuntimeError(f"{len(sim.outbox)} events never acked")
    return time.perf_counter() - start


def main(args) -> int:
    import uvicorn

    from app.api import create_app
    from app.bridge import bridge_for
    from app.bridge.protocol import MAX_FRAME_BYTES
    from app.pipeline import Pipeline
    from models.language import RuleParser
    from frontend.server import free_port
    from studio_db import Store

    n = max(args.n, 1000) if args.n != 30 else 20_000
    tmp = tempfile.mkdtemp(prefix="h3ds-bench-bridge-")
    store = Store(f"sqlite:///{tmp}/studio.db")
    pipeline = Pipeline(parser=RuleParser())  # the rules, as the figures in the README
    scene = pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0).scene
    scene_id, _ = store.create_scene("bench", scene, 0, "dfs")
    bridge = bridge_for(store)
    port = free_port("127.0.0.1", 18900)
    server = uvicorn.Server(uvicorn.Config(create_app(store, pipeline), host="127.0.0.1", port=port,
                                          log_level="warning", ws_max_size=MAX_FRAME_BYTES))
    threading.Thread(target=server.run, daemon=True).start()
    while not server.started:
        time.sleep(0.02)
    HeadsetSimulator = _simulator()

    async def run(rate: float | None, count: int) -> dict:
        timed = _Timed()
        unsubscribe = bridge.subscribe(timed)
        sim = HeadsetSimulator(f"ws://127.0.0.1:{port}/headset", bridge.token, validate=False)
        await sim.connect()
        await asyncio.to_thread(bridge.push, sim.session, scene_id, 1)
        push = await asyncio.wait_for(sim.pushes.get(), 30)
        seconds = await _stream(sim, push["push"], count, rate)
        await sim.close()
        unsubscribe()
        stored = bridge.feedback.count(sim.session)
        lat = np.array(timed.latency_ms)
        return {"events": count, "stored": stored, "seconds": round(seconds, 3),
                "events_per_s": round(count / seconds, 1), "latency_ms_p50": round(float(np.percentile(lat, 50)), 2),
                "latency_ms_p99": round(float(np.percentile(lat, 99)), 2), "panel_total": timed.view.total}

    saturated = asyncio.run(run(None, n))
    paced = asyncio.run(run(1000.0, min(n, 5000)))
    server.should_exit = True

    # baseline: the same events, one store transaction each, no websocket (a fraction of n: it is slow)
    k = 1000
    msgs = [{"id": f"b{i}", "seq": i + 1, "ts": time.time(), "body": {
        "push": next(iter(bridge.feedback.push_ids())), "t": 0.0, "object_id": "Bread|1", "object_type": "Bread",
        "kind": "hover", "hand": "right", "fingers": ["index"], "haptic_class": "cold", "intensity": 55,
        "glove_colour": [0, 0.35, 1]}} for i in range(k)]
    start = time.perf_counter()
    for m in msgs:
        bridge.feedback.add_events("baseline", [m])
    per_event = k / (time.perf_counter() - start)

    result = {"saturated": saturated, "paced_1000_per_s": paced,
              "baseline_one_transaction_per_event": {"events": k, "events_per_s": round(per_event, 1)},
              "ratio_bridge_over_baseline": round(saturated["events_per_s"] / per_event, 2),
              "window": WINDOW, "machine": f"{platform.machine()}, {platform.python_version()}",
              "note": "headset simulator (stand-in) and studio in one process on loopback; latency = event "
                      "creation on the headset -> stored and applied to the feedback panel's model"}
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "bridge.json").write_text(json.dumps(result, indent=2) + "\n")
    lines = ["# h3ds bench bridge", "", "| run | events | stored | events/s | p50 ms | p99 ms |", "|---|---|---|---|---|---|"]
    for name, r in (("saturated (window 1000)", saturated), ("paced 1,000/s", paced)):
        lines.append(f"| {name} | {r['events']} | {r['stored']} | {r['events_per_s']} | {r['latency_ms_p50']} | "
                     f"{r['latency_ms_p99']} |")
    lines += [f"| baseline: 1 transaction/event, no socket | {k} | {k} | {round(per_event, 1)} | | |", "",
              f"bridge / baseline throughput: {result['ratio_bridge_over_baseline']}x", "", result["note"]]
    (RESULTS / "bridge.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    ok = saturated["stored"] == n and paced["stored"] == paced["events"]
    return 0 if ok else 1
