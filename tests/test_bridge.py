"""The headset link over real websockets on loopback: the studio's API server (uvicorn) and the headset
simulator (the stand-in for the Quest app, which speaks only the wire protocol).

End to end (pair, push, load, robot steps, glove events stored once and exported), and reliability: a
drop in the middle of 10,000 glove events, malformed / unknown / wrong-version / oversized / invalid
messages, wrong tokens and a flood, after each of which the server still answers and nothing stored is
lost or duplicated.
"""

from __future__ import annotations

import asyncio
import importlib.util
import json
import threading
import time
from pathlib import Path

import pytest
import uvicorn
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed

from app.api import create_app
from app.bridge import bridge_for
from app.bridge.protocol import MAX_FRAME_BYTES
from frontend.server import free_port
from studio_db import Store

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("headset_sim", ROOT / "unity-bridge" / "simulator" / "headset_sim.py")
sim_mod = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(sim_mod)
HeadsetSimulator, Refused = sim_mod.HeadsetSimulator, sim_mod.Refused


@pytest.fixture(scope="module")
def scene(pipeline):
    """A kitchen whose robot plan reaches every task object (DFS leaves the fridge unreachable at seeds 0 and 4)."""
    return pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=1).scene


class Server:
    def __init__(self, url: str, pipeline):
        self.store = Store(url)
        self.bridge = bridge_for(self.store)
        self.port = free_port("127.0.0.1", 18700)
        self.server = uvicorn.Server(uvicorn.Config(create_app(self.store, pipeline), host="127.0.0.1",
                                                    port=self.port, log_level="warning", ws_max_size=MAX_FRAME_BYTES))
        self.thread = threading.Thread(target=self.server.run, daemon=True)
        self.thread.start()
        while not self.server.started:
            time.sleep(0.02)
        self.url = f"ws://127.0.0.1:{self.port}/headset"

    def stop(self):
        self.server.should_exit = True
        self.thread.join(10)


@pytest.fixture
def server(tmp_path, pipeline, scene):
    s = Server(f"sqlite:///{tmp_path / 'studio.db'}", pipeline)
    s.scene_id, _ = s.store.create_scene("bread", scene, 0, "dfs")
    yield s
    s.stop()


def run(coro):
    return asyncio.run(asyncio.wait_for(coro, 120))


async def paired_with_scene(server: Server, scene_id: int | None = None, **kw) -> tuple[HeadsetSimulator, dict]:
    sim = HeadsetSimulator(server.url, server.bridge.token, **kw)
    await sim.connect()
    await asyncio.to_thread(server.bridge.push, sim.session, scene_id or server.scene_id, 1)
    push = await asyncio.wait_for(sim.pushes.get(), 30)
    return sim, push


def stored_seqs(server: Server, session: str) -> list[int]:
    return sorted(r["seq"] for r in server.bridge.feedback.records(session=session))


def test_pair_push_run_and_export(server, scene):
    seen = []
    server.bridge.subscribe(lambda kind, payload: seen.append((kind, payload)))

    async def go():
        sim, push = await paired_with_scene(server)
        assert push["house"]["metadata"]["schema"] == "1.0.0" and push["robot_plan"]["steps"]
        assert not push["robot_plan"]["problems"]
        assert push["vr_start_pose"]["best"] is not None and push["haptic_profiles"]
        counts = await sim.run_scene(push)
        assert await sim.wait_acked(30)
        await sim.close(end_session=True)
        return sim, push, counts

    sim, push, counts = run(go())
    assert counts["loaded"] and counts["failed_steps"] == 0 and counts["glove_events"] > 0
    progress = server.bridge.progress[push["push"]]
    assert progress.delivered and progress.loaded and progress.step == progress.steps == counts["steps"]
    assert progress.decision == "accept" and f"robot step {progress.steps} of {progress.steps}" in progress.text()
    records = list(server.bridge.feedback.records(session=sim.session))
    assert len(records) == counts["glove_events"] == len({r["seq"] for r in records})
    r = records[0]
    assert r["scene_id"] == server.scene_id and r["scene_version"] == 1 and r["task_type"] == scene.task_graph.task_type
    assert json.loads(r["task_graph"])["instruction"] == scene.task_graph.instruction
    assert {x["kind"] for x in records} == {"hover", "select", "unselect", "unhover"}
    # the bread was cooled in the fridge by the robot: touching it afterwards is cold and tints the glove blue
    cooled = [x for x in records if x["object_type"] == "Bread" and x["kind"] == "select" and x["haptic_class"] == "cold"]
    assert cooled and cooled[-1]["glove_colour"][2] > 0.5
    streamed = sum(len(p) for k, p in seen if k == "feedback")
    assert streamed == len(records)
    assert sim.session not in {h.session for h in server.bridge.paired()}  # session_end forgets it


def test_a_stored_apartment_is_pushed_and_run_through_its_doors(server, pipeline):
    apartment = pipeline.generate_apartment("Pick up a mug from the desk, turn on the lamp", None, seed=2)
    mug_room, lamp_room = (apartment.plan.assignment[t] for t in ("Mug", "DeskLamp"))
    assert mug_room != lamp_room  # the robot has to walk from one room to the other
    flat_id, _ = server.store.create_scene("flat", apartment, 2, "dfs")

    async def go():
        sim, push = await paired_with_scene(server, flat_id)
        counts = await sim.run_scene(push)
        assert await sim.wait_acked(30)
        await sim.close(end_session=True)
        return sim, push, counts

    sim, push, counts = run(go())
    assert push["scene_id"] == flat_id and [r["id"] for r in push["house"]["rooms"]] == \
        [hr.id for hr in apartment.floorplan.rooms]
    assert push["vr_start_pose"]["best"] == apartment.vr_anchor.model_dump(mode="json")
    assert not push["robot_plan"]["problems"] and counts["loaded"] and counts["failed_steps"] == 0
    progress = server.bridge.progress[push["push"]]
    assert progress.loaded and progress.step == progress.steps == counts["steps"] > 0
    records = list(server.bridge.feedback.records(session=sim.session))
    assert len(records) == counts["glove_events"]
    assert {r["scene_id"] for r in records} == {flat_id} and records[0]["room_type"] == "apartment"
    touched = {r["object_id"] for r in records}
    assert f"Mug|surface|{mug_room[-1]}|0" in touched and f"DeskLamp|surface|{lamp_room[-1]}|0" in touched
    profiles = {p["object_id"]: p for p in push["haptic_profiles"]}
    assert profiles[f"DeskLamp|surface|{lamp_room[-1]}|0"]["haptic_class"] == "light"


def test_export_filters_and_loads_with_datasets(server, tmp_path):
    from fastapi.testclient import TestClient

    async def go():
        sims = []
        for seed in (1, 2):
            sim, push = await paired_with_scene(server, seed=seed)
            await sim.run_scene(push)
            assert await sim.wait_acked(30)
            await sim.close()
            sims.append(sim)
        return sims

    a, b = run(go())
    api = TestClient(create_app(server.store))
    everything = api.get("/feedback", params={"format": "jsonl"}).text.splitlines()
    only_a = api.get("/feedback", params={"session": a.session}).text.splitlines()
    assert len(everything) == len(stored_seqs(server, a.session)) + len(stored_seqs(server, b.session))
    assert only_a and all(json.loads(x)["session"] == a.session for x in only_a)
    assert api.get("/feedback", params={"scene_id": 999}).text == ""
    assert api.get("/feedback", params={"since": "2999-01-01"}).text == ""
    assert len(api.get("/feedback", params={"since": "2000-01-01"}).text.splitlines()) == len(everything)
    assert api.get("/feedback", params={"since": "yesterday"}).status_code == 422
    path = tmp_path / "feedback.jsonl"
    path.write_text("\n".join(everything) + "\n")
    import datasets
    ds = datasets.load_dataset("json", data_files=str(path), split="train", cache_dir=str(tmp_path / "hf"))
    assert ds.num_rows == len(everything)
    assert ds[0]["object_id"] and isinstance(ds[0]["fingers"], list) and len(ds[0]["glove_colour"]) == 3


def test_drop_in_the_middle_of_10000_events_stores_each_once(server):
    n = 10_000

    async def go():
        sim, push = await paired_with_scene(server, validate=False)
        for i in range(n):
            if i == n // 2:
                await sim.drop()  # abrupt: whatever was in flight is unacked and will be resent
            if i == n // 2 + 500:
                await sim.connect()  # resume key, not the (rotated) token
            await sim.glove_event(push["push"], i * 0.01, "Bread|1", "Bread", "hover", "right", ["index"], "normal",
                                  30, [0, 0, 0])
        assert await sim.wait_acked(90), f"{len(sim.outbox)} events never acked"
        await sim.close()
        return sim

    sim = run(go())
    seqs = stored_seqs(server, sim.session)
    first = min(seqs)
    assert seqs == list(range(first, first + n))  # every event, exactly once
    assert server.bridge.feedback.count(sim.session) == n


def test_bad_messages_get_clear_errors_and_lose_nothing(server):
    async def go():
        sim, push = await paired_with_scene(server)
        for i in range(20):
            await sim.glove_event(push["push"], i, "Bread|1", "Bread", "select", "left", ["thumb"], "cold", 50,
                                  [0, 0.35, 1])
        assert await sim.wait_acked(30)
        before = stored_seqs(server, sim.session)
        good = sim.make("glove_event", {"push": push["push"], "t": 1.0, "object_id": "Bread|1", "object_type": "Bread",
                                        "kind": "hover", "hand": "left", "fingers": [], "haptic_class": "normal",
                                        "intensity": 0, "glove_colour": [0, 0, 0]})
        bad = {
            "malformed": "{not json",
            "unknown_type": json.dumps({**good, "type": "teleport"}),
            "bad_version": json.dumps({**good, "version": 2}),
            "invalid": json.dumps({**good, "body": {**good["body"], "hand": "third"}}),
            "too_large": json.dumps({**good, "body": {**good["body"], "object_type": "x" * 70_000}}),
            "unknown_push": json.dumps({**good, "body": {**good["body"], "push": "nope"}}),
        }
        for code, frame in bad.items():
            await sim.ws.send(frame)
        deadline = time.monotonic() + 10
        while len(sim.errors) < len(bad) and time.monotonic() < deadline:
            await asyncio.sleep(0.05)
        codes = [e["code"] for e in sim.errors]
        # still connected and working: the valid event (the bad frames' seq) is stored and acked
        await sim.send_made(good)
        assert await sim.wait_acked(10)
        await sim.close()
        return sim, codes, before

    sim, codes, before = run(go())
    assert codes == ["malformed", "unknown_type", "bad_version", "invalid", "too_large", "unknown_push"]
    assert all(e["message"] and not e["fatal"] for e in sim.errors)
    assert "hand" in sim.errors[3]["message"] and "65536" in sim.errors[4]["message"]
    assert stored_seqs(server, sim.session) == before + [max(before) + 1]


def test_wrong_token_and_unpaired_are_refused_and_the_server_survives(server):
    async def go():
        wrong = "000000" if server.bridge.token != "000000" else "111111"
        with pytest.raises(Refused, match="wrong_token"):
            await HeadsetSimulator(server.url, wrong).connect()
        with pytest.raises(Refused, match="invalid: pair"):
            await HeadsetSimulator(server.url, "12345", validate=False).connect()  # not six digits: the schema refuses it
        async with connect(server.url) as ws:  # a glove event before pairing
            sim = HeadsetSimulator(server.url)
            await ws.send(json.dumps(sim.make("glove_event", {
                "push": "p", "t": 0, "object_id": "Bread|1", "object_type": "Bread", "kind": "hover", "hand": "left",
                "fingers": [], "haptic_class": "normal", "intensity": 0, "glove_colour": [0, 0, 0]})))
            reply = json.loads(await ws.recv())
            assert reply["body"]["code"] == "unpaired" and reply["body"]["fatal"]
            with pytest.raises(ConnectionClosed) as closed:
                await ws.recv()
            assert closed.value.rcvd.code == 4001
        sim = HeadsetSimulator(server.url, server.bridge.token)
        await sim.connect()  # the right token still pairs
        await sim.close()

    run(go())


def test_a_flood_is_stored_once_and_the_server_still_answers(server):
    n = 5000

    async def go():
        sim, push = await paired_with_scene(server, validate=False)
        frames = []
        for i in range(n):
            msg = sim.make("glove_event", {"push": push["push"], "t": i, "object_id": "Bread|1", "object_type": "Bread",
                                           "kind": "hover", "hand": "left", "fingers": [], "haptic_class": "normal",
                                           "intensity": 0, "glove_colour": [0, 0, 0]})
            sim.outbox[msg["id"]] = msg
            frames.append(json.dumps(msg))
        sim._acked.clear()
        for f in frames + frames[:1000]:  # everything as fast as the socket takes it, 1000 of them twice
            await sim.ws.send(f)
        assert await sim.wait_acked(90)
        await sim.send("ping", {})
        await sim.close()
        return sim

    sim = run(go())
    assert server.bridge.feedback.count(sim.session) == n
    assert stored_seqs(server, sim.session) == list(range(1, n + 1))


def test_a_frame_over_the_websocket_limit_closes_only_that_connection(server):
    async def go():
        sim, push = await paired_with_scene(server)
        await sim.glove_event(push["push"], 0.0, "Bread|1", "Bread", "hover", "left", [], "normal", 0, [0, 0, 0])
        assert await sim.wait_acked(10)
        ws = sim.ws
        await ws.send("x" * (MAX_FRAME_BYTES + 1))
        await asyncio.wait_for(sim._reader, 10)  # the reader ends when the studio closes the socket
        assert ws.close_code == 1009  # message too big
        await sim.connect()  # the server lives on: the same session resumes
        await sim.glove_event(push["push"], 1.0, "Bread|1", "Bread", "unhover", "left", [], "normal", 0, [0, 0, 0])
        assert await sim.wait_acked(10)
        await sim.close()
        return sim

    sim = run(go())
    assert stored_seqs(server, sim.session) == [1, 2]
