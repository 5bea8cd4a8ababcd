"""STAND-IN for the Meta Quest headset running the Unity/AI2-THOR app: the H3DS headset simulator.

It speaks exactly the headset protocol (unity-bridge/protocol/v1, validated against those schema files
both ways) over a real websocket and reaches the studio only through it: it imports nothing from the
studio (app/, frontend/, studio_db/), only the value types and the symbolic executor of models/. It
pairs, receives a scene push, "loads" it (builds the symbolic state of the house JSON instead of calling
AI2-THOR's CreateHouse), runs the robot plan step by step on that state, and emits the glove events of a
person touching the task objects as the robot works; it keeps every message until it is acked and
resends the unacked ones after a reconnect.

Run: python unity-bridge/simulator/headset_sim.py ws://127.0.0.1:8081/headset --token 123456
"""

from __future__ import annotations

import argparse
import asyncio
import json
import random
import sys
import time
import uuid
from pathlib import Path

from jsonschema import Draft202012Validator
from websockets.asyncio.client import ClientConnection, connect
from websockets.exceptions import ConnectionClosed

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from models.interaction import SymbolicState, execute_step  # noqa: E402  (value types and executor only)

VERSION = 1
SCHEMAS = Path(__file__).resolve().parents[1] / "protocol" / f"v{VERSION}"
DEVICE = "H3DS headset simulator (stand-in for Meta Quest + bHaptics TactGloves)"
UNNUMBERED = frozenset({"hello", "pair", "ack", "pong", "error"})  # seq 0, never resent
NEUTRAL = [0.0, 0.0, 0.0]


def _validators() -> dict[str, Draft202012Validator]:
    return {p.name.removesuffix(".schema.json"): Draft202012Validator(json.loads(p.read_text()))
            for p in SCHEMAS.glob("*.schema.json") if p.name != "envelope.schema.json"}


class Refused(Exception):
    """The studio refused the connection (wrong token, unpaired); the error's message says why."""


class HeadsetSimulator:
    def __init__(self, url: str, token: str | None = None, *, session: str | None = None, seed: int = 0,
                 device: str = DEVICE, validate: bool = True):
        self.url, self.token, self.device = url, token, device
        self.session = session or uuid.uuid4().hex
        self.rng = random.Random(seed)
        self.validators = _validators() if validate else None
        self.seq = 0
        self.outbox: dict[str, dict] = {}  # id -> message, until the studio acks it
        self.duplicates = 0  # acks with duplicate: true (resends the studio had stored)
        self.errors: list[dict] = []
        self.pushes: asyncio.Queue = asyncio.Queue()
        self.resume_key: str | None = None
        self.last_seq = 0
        self.ws: ClientConnection | None = None
        self._reader: asyncio.Task | None = None
        self._acked = asyncio.Event()

    # ---- messages --------------------------------------------------------------------------------

    def _check(self, msg: dict) -> None:
        if self.validators is not None:
            error = next(iter(self.validators[msg["type"]].iter_errors(msg)), None)
            if error is not None:
                raise ValueError(f"{msg['type']} does not match its schema: {error.message}")

    def make(self, kind: str, body: dict) -> dict:
        if kind not in UNNUMBERED:
            self.seq += 1
        msg = {"version": VERSION, "type": kind, "session": self.session, "id": uuid.uuid4().hex,
               "seq": 0 if kind in UNNUMBERED else self.seq, "ts": time.time(), "body": body}
        self._check(msg)
        return msg

    async def send(self, kind: str, body: dict) -> dict:
        """Send a message; a numbered one is kept until acked (and resent after a reconnect)."""
        return await self.send_made(self.make(kind, body))

    async def send_made(self, msg: dict) -> dict:
        """Send a message built by `make`, kept until acked like any other."""
        if msg["type"] not in UNNUMBERED:
            self.outbox[msg["id"]] = msg
            self._acked.clear()
        await self._transmit(msg)
        return msg

    async def _transmit(self, msg: dict) -> None:
        if self.ws is None:
            return
        try:
            await self.ws.send(json.dumps(msg))
        except ConnectionClosed:
            self.ws = None  # kept in the outbox: resent after reconnecting

    # ---- connection ------------------------------------------------------------------------------

    async def connect(self) -> dict:
        """Connect, say hello, pair (token the first time, resume key after) and resend what was not acked.
        Returns the studio's `paired` body; raises Refused when the studio says no."""
        ws = await connect(self.url, max_size=None)
        await ws.send(json.dumps(self.make("hello", {
            "role": "headset", "device": self.device, "app_version": "sim-1",
            "capabilities": ["symbolic-ai2thor", "hand-tracking", "bhaptics"], "gloves": {"left": True, "right": True}})))
        await self._expect(ws, "hello")
        pair = {"resume_key": self.resume_key} if self.resume_key else {"token": self.token or ""}
        await ws.send(json.dumps(self.make("pair", pair)))
        paired = await self._expect(ws, "paired")
        self.resume_key, self.last_seq = paired["resume_key"], paired["last_seq"]
        self.ws = ws
        self._reader = asyncio.create_task(self._read(ws))
        for msg in sorted(self.outbox.values(), key=lambda m: m["seq"]):
            await self._transmit(msg)
        return paired

    async def _expect(self, ws: ClientConnection, kind: str) -> dict:
        try:
            msg = json.loads(await asyncio.wait_for(ws.recv(), 10))
        except ConnectionClosed as e:
            raise Refused(f"closed by the studio ({e.rcvd.code if e.rcvd else '?'})") from None
        self._check(msg)
        if msg["type"] == "error":
            await ws.close()
            raise Refused(f"{msg['body']['code']}: {msg['body']['message']}")
        if msg["type"] != kind:
            raise Refused(f"expected {kind}, got {msg['type']}")
        return msg["body"]

    async def _read(self, ws: ClientConnection) -> None:
        try:
            async for raw in ws:
                msg = json.loads(raw)
                self._check(msg)
                kind, body = msg["type"], msg["body"]
                if kind == "ack":
                    if self.outbox.pop(body["of"], None) is not None and body.get("duplicate"):
                        self.duplicates += 1
                    if not self.outbox:
                        self._acked.set()
                elif kind == "scene_push":
                    await self._transmit(self.make("ack", {"of": msg["id"], "seq": msg["seq"]}))
                    await self.pushes.put(body)
                elif kind == "ping":
                    await self._transmit(self.make("pong", {"ping": msg["id"]}))
                elif kind == "error":
                    self.errors.append(body)
        except ConnectionClosed:
            pass
        finally:
            if self.ws is ws:
                self.ws = None

    async def drop(self) -> None:
        """Lose the connection abruptly (no close handshake), as a headset leaving Wi-Fi does."""
        ws, self.ws = self.ws, None
        if ws is not None:
            ws.transport.abort()
            if self._reader is not None:
                await asyncio.gather(self._reader, return_exceptions=True)

    async def close(self, end_session: bool = False) -> None:
        if end_session and self.ws is not None:
            await self.send("session_end", {"reason": "the person took the headset off"})
            await self.wait_acked(10)
        if self.ws is not None:
            await self.ws.close()
        if self._reader is not None:
            await asyncio.gather(self._reader, return_exceptions=True)
        self.ws = None

    async def wait_acked(self, timeout: float) -> bool:
        """Wait until every numbered message has been acked."""
        if not self.outbox:
            return True
        try:
            await asyncio.wait_for(self._acked.wait(), timeout)
            return True
        except asyncio.TimeoutError:
            return not self.outbox

    # ---- a scene ---------------------------------------------------------------------------------

    async def run_scene(self, push: dict, pace_s: float = 0.0, decide: str = "accept") -> dict:
        """Load the pushed house (symbolic stand-in for CreateHouse), run the robot plan, touch the task
        objects around each step, then send the person's decision. Returns counts of what was sent."""
        start = time.monotonic()
        try:
            state = SymbolicState.from_house(push["house"])
        except Exception as e:  # noqa: BLE001 - any reason the house cannot be built is reported
            await self.send("scene_failed", {"push": push["push"], "reason": f"house could not be built: {e}"})
            return {"loaded": False}
        await self.send("scene_loaded", {"push": push["push"], "load_ms": (time.monotonic() - start) * 1000,
                                         "objects": len(state.objects)})
        profiles = {p["object_id"]: p for p in push["haptic_profiles"]}
        steps, events, failed = push["robot_plan"]["steps"], 0, 0
        for step in steps:
            target = step.get("target") or step["action"].get("objectId")
            if target in state.objects:
                events += await self.touch(push["push"], state, target, profiles, start)
            state, result = execute_step(state, step)
            failed += not result.ok
            await self.send("plan_step_result", {"push": push["push"], "index": step["index"], "of": len(steps),
                                                 "action": step["action"]["action"], "ok": result.ok,
                                                 "message": result.message[:2000]})
            if pace_s:
                await asyncio.sleep(pace_s)
        await self.send("user_decision", {"push": push["push"], "decision": decide,
                                          "comment": "stand-in decision by the headset simulator"})
        return {"loaded": True, "steps": len(steps), "failed_steps": failed, "glove_events": events}

    async def touch(self, push_id: str, state: SymbolicState, object_id: str, profiles: dict, start: float) -> int:
        """A person reaches for an object: hover, select (grasp), unselect, unhover, with the haptics and
        glove colour its profile (and its symbolic temperature: cooled -> cold, heated -> hot) give."""
        obj = state.objects[object_id]
        profile = profiles.get(object_id)
        cls = "hot" if obj.heated else "cold" if obj.cooled else (profile["haptic_class"] if profile else "normal")
        hand = "right" if self.rng.random() < 0.8 else "left"
        touch = profile["touch"]["intensities"] if profile else [0, 30, 0, 0, 0, 0]
        grasp = profile["grasp"]["intensities"] if profile else [30, 30, 20, 0, 0, 0]
        colour = list(profile["colour"]["end"]) if profile else NEUTRAL
        if profile and cls != profile["haptic_class"]:
            colour = {"cold": [0.0, 0.35, 1.0], "hot": [1.0, 0.45, 0.0]}.get(cls, colour)
        grasping = [f for f, v in zip(("thumb", "index", "middle", "ring", "little"), grasp) if v > 0] or ["index"]
        sequence = [("hover", ["index"], max(touch), NEUTRAL), ("select", grasping, max(grasp), colour),
                    ("unselect", [], 0, colour), ("unhover", [], 0, NEUTRAL)]
        for kind, fingers, intensity, tint in sequence:
            await self.glove_event(push_id, time.monotonic() - start, object_id, obj.type, kind, hand, fingers,
                                   cls, intensity, tint)
        return len(sequence)

    async def glove_event(self, push_id: str, t: float, object_id: str, object_type: str, kind: str, hand: str,
                          fingers: list[str], haptic_class: str, intensity: int, colour: list[float]) -> dict:
        return await self.send("glove_event", {
            "push": push_id, "t": round(max(t, 0.0), 4), "object_id": object_id, "object_type": object_type,
            "kind": kind, "hand": hand, "fingers": fingers, "haptic_class": haptic_class,
            "intensity": int(intensity), "glove_colour": [float(c) for c in colour]})


async def _next_push(sim: HeadsetSimulator, retries: int = 5) -> dict | None:
    """The next scene push; after a drop, reconnect (resume key) up to `retries` times, else None."""
    while True:
        waiting = asyncio.ensure_future(sim.pushes.get())
        await asyncio.wait([waiting, sim._reader], return_when=asyncio.FIRST_COMPLETED)
        if waiting.done():
            return waiting.result()
        waiting.cancel()
        for _ in range(retries):
            await asyncio.sleep(1.0)
            try:
                await sim.connect()
                break
            except (OSError, Refused):
                continue
        else:
            return None


async def _main(args) -> int:
    sim = HeadsetSimulator(args.url, args.token, seed=args.seed)
    paired = await sim.connect()
    print(f"[stand-in headset] paired as {paired['headset_id']} (session {sim.session}); waiting for scenes",
          flush=True)
    while True:
        push = await _next_push(sim)
        if push is None:
            print("[stand-in headset] the studio is gone; exiting", flush=True)
            return 1
        print(f"[stand-in headset] scene {push['scene_id']} v{push['version']}: {len(push['robot_plan']['steps'])} "
              f"robot steps", flush=True)
        counts = await sim.run_scene(push, pace_s=args.pace)
        await sim.wait_acked(30)
        print(f"[stand-in headset] done: {counts}", flush=True)
        if args.once:
            await sim.close(end_session=True)
            return 0


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description="The headset simulator (a stand-in for the Quest app).")
    parser.add_argument("url", help="the studio's headset address, e.g. ws://127.0.0.1:8081/headset")
    parser.add_argument("--token", required=True, help="the pairing token shown in the studio's Headset tab")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--pace", type=float, default=0.5, help="seconds between robot steps")
    parser.add_argument("--once", action="store_true", help="end the session after one scene")
    sys.exit(asyncio.run(_main(parser.parse_args())))
