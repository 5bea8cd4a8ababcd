"""The studio's end of the headset link: pairing tokens, paired headsets, scene pushes and their progress,
and glove events stored as feedback (acked only after the write commits) and handed to listeners (the
studio's feedback panels). Thread-safe: the websocket runs on the API server's event loop, the studio's
buttons call `push` from viser's threads.
"""

from __future__ import annotations

import asyncio
import json
import logging
import secrets
import threading
import time
import weakref
from dataclasses import dataclass, field
from typing import Callable

from fastapi import WebSocket, WebSocketDisconnect

from app.bridge.protocol import MAX_MESSAGE_BYTES, ProtocolError, message, parse
from studio_db import Store
from studio_db.feedback import FeedbackStore

log = logging.getLogger(__name__)
TOKEN_TTL_S = 300.0
CLOSE_UNPAIRED, CLOSE_WRONG_TOKEN = 4001, 4003
ANSWERED = frozenset({"hello", "pair", "ping", "pong", "ack", "error"})  # not acked: answered otherwise
STUDIO = "H3DS Studio"


@dataclass
class Progress:
    """What became of one scene push (shown in the Headset tab)."""

    push: str
    session: str
    scene_id: int
    version: int
    steps: int
    delivered: bool = False
    loaded: bool | None = None
    failure: str = ""
    step: int = 0  # robot steps reported so far
    failed_steps: int = 0
    decision: str = ""

    def text(self) -> str:
        if self.loaded is False:
            return f"failed to load: {self.failure}"
        parts = ["delivered" if self.delivered else "sending"]
        if self.loaded:
            parts += ["loaded", f"robot step {self.step} of {self.steps}"]
            if self.failed_steps:
                parts.append(f"{self.failed_steps} step(s) failed")
        if self.decision:
            parts.append(f"user {self.decision}ed")
        return ", ".join(parts)


@dataclass
class Headset:
    session: str
    headset_id: str
    device: str
    gloves: dict
    capabilities: list[str]
    resume_key: str
    connected: bool = False
    seq: int = 0  # the studio's own sequence in this session
    socket: "Connection | None" = None
    handled: set[int] = field(default_factory=set)  # seqs of non-glove messages already applied


class Connection:
    """One websocket: serialises sends, carries the loop so other threads can send."""

    def __init__(self, ws: WebSocket):
        self.ws = ws
        self.loop = asyncio.get_running_loop()
        self.lock = asyncio.Lock()

    async def send(self, msg: dict) -> None:
        async with self.lock:
            await self.ws.send_text(json.dumps(msg))


class Bridge:
    def __init__(self, store: Store, token_ttl_s: float = TOKEN_TTL_S):
        self.store = store
        self.feedback = FeedbackStore(store)
        self.token_ttl_s = token_ttl_s
        self._lock = threading.RLock()
        self._token, self._token_expires = "", 0.0
        self.headsets: dict[str, Headset] = {}
        self.progress: dict[str, Progress] = {}
        self._pushes = self.feedback.push_ids()
        self._listeners: list[Callable[[str, object], None]] = []
        self.address = ""  # ws://host:port/headset once the API server runs (shown in the Headset tab)

    # ---- pairing ---------------------------------------------------------------------------------

    @property
    def token(self) -> str:
        """The current pairing token (a new one once the old has expired)."""
        with self._lock:
            if time.monotonic() >= self._token_expires:
                self.new_token()
            return self._token

    def token_expires_in(self) -> float:
        return max(0.0, self._token_expires - time.monotonic())

    def new_token(self) -> str:
        with self._lock:
            self._token = f"{secrets.randbelow(10**6):06d}"
            self._token_expires = time.monotonic() + self.token_ttl_s
            return self._token

    def paired(self) -> list[Headset]:
        with self._lock:
            return list(self.headsets.values())

    # ---- listeners -------------------------------------------------------------------------------

    def subscribe(self, fn: Callable[[str, object], None]) -> Callable[[], None]:
        """fn(kind, payload) for 'feedback' (list of stored glove_event messages), 'progress' (Progress)
        and 'headsets' (None); returns the unsubscribe function."""
        with self._lock:
            self._listeners.append(fn)
        return lambda: self._listeners.remove(fn) if fn in self._listeners else None

    def _publish(self, kind: str, payload: object) -> None:
        for fn in list(self._listeners):
            try:
                fn(kind, payload)
            except Exception:  # a broken panel must not break the link
                log.exception("headset listener failed")

    # ---- pushing a scene ---------------------------------------------------------------------------

    def push(self, session: str, scene_id: int, version: int, timeout: float = 30.0) -> Progress:
        """Send a stored scene version to a paired, connected headset (from any thread but the loop's)."""
        from app.bridge.content import push_content

        with self._lock:
            headset = self.headsets.get(session)
        if headset is None or not headset.connected or headset.socket is None:
            raise LookupError(f"headset session {session!r} is not connected")
        scene = self.store.scene(scene_id, version)  # a single room or an apartment
        content = push_content(scene)
        name = next((v["name"] for v in self.store.versions(scene_id) if v["number"] == version), "")
        with self._lock:
            headset.seq += 1
            msg = message("scene_push", session, headset.seq, {})
        push_id = msg["id"]
        msg["body"] = {
            "push": push_id, "scene_id": scene_id, "version": version, "name": name,
            "instruction": scene.task_graph.instruction if scene.task_graph else "", "house": content.house,
            "vr_start_pose": content.vr_start_pose.model_dump(mode="json"),
            "haptic_profiles": [p.model_dump(mode="json") for p in content.haptic_profiles],
            "robot_plan": content.plan.model_dump(mode="json"),
        }
        self.feedback.add_push(push_id, session, headset.headset_id, headset.device, scene_id, version)
        progress = Progress(push_id, session, scene_id, version, steps=len(content.plan.steps))
        with self._lock:
            self._pushes.add(push_id)
            self.progress[push_id] = progress
        conn = headset.socket
        asyncio.run_coroutine_threadsafe(conn.send(msg), conn.loop).result(timeout)
        self._publish("progress", progress)
        return progress

    # ---- the websocket ---------------------------------------------------------------------------

    async def serve(self, ws: WebSocket) -> None:
        await ws.accept()
        conn = Connection(ws)
        headset: Headset | None = None
        hello: dict | None = None
        queue: asyncio.Queue = asyncio.Queue()
        writer: asyncio.Task | None = None
        try:
            while True:
                frame = await ws.receive()
                if frame["type"] == "websocket.disconnect":
                    break
                raw = frame.get("text") if frame.get("text") is not None else frame.get("bytes") or b""
                try:
                    msg = parse(raw)
                except ProtocolError as e:
                    await self._error(conn, headset, e.code, e.message, e.of)
                    continue
                if headset is None:
                    result, hello = await self._pairing(conn, msg, hello)
                    if result is False:
                        return
                    headset = result
                    if headset is not None:
                        writer = asyncio.create_task(self._writer(conn, headset, queue))
                    continue
                if msg["session"] != headset.session:
                    await self._error(conn, headset, "invalid", f"this connection is paired as session "
                                      f"{headset.session!r}, not {msg['session']!r}", msg["id"])
                    continue
                await queue.put(msg)
        except WebSocketDisconnect:
            pass
        finally:
            if writer is not None:
                await queue.put(None)
                await writer
            if headset is not None:
                with self._lock:
                    if headset.socket is conn:
                        headset.connected, headset.socket = False, None
                self._publish("headsets", None)

    async def _pairing(self, conn: Connection, msg: dict, hello: dict | None):
        """Before pairing: hello, then pair. Returns (headset or None, hello); headset False = refused."""
        kind = msg["type"]
        if kind == "hello" and hello is None:
            reply = message("hello", msg["session"], 0, {"role": "studio", "device": STUDIO, "app_version": "1",
                                                        "max_message_bytes": MAX_MESSAGE_BYTES})
            await conn.send(reply)
            return None, msg
        if kind == "ping":
            await conn.send(message("pong", msg["session"], 0, {"ping": msg["id"]}))
            return None, hello
        if kind != "pair" or hello is None:
            await self._refuse(conn, msg, "unpaired", "pair first: send hello, then pair with the studio's token",
                               CLOSE_UNPAIRED)
            return False, hello
        body, session = msg["body"], msg["session"]
        with self._lock:
            existing = self.headsets.get(session)
            if "resume_key" in body:
                ok = existing is not None and secrets.compare_digest(existing.resume_key, body["resume_key"])
                why = "unknown session or resume key; pair again with the studio's token"
            else:
                ok = secrets.compare_digest(self.token, body["token"])
                why = "wrong or expired pairing token; read the token in the studio's Headset tab"
            if ok:
                h = hello["body"]
                headset = existing if "resume_key" in body else Headset(
                    session, f"headset-{len(self.headsets) + 1}", h["device"], h.get("gloves", {}),
                    h.get("capabilities", []), secrets.token_urlsafe(24))
                if "token" in body:
                    self.new_token()  # a token pairs one headset
                    self.headsets[session] = headset
                headset.connected, headset.socket = True, conn
                headset.seq += 1
                seq = headset.seq
        if not ok:
            await self._refuse(conn, msg, "wrong_token", why, CLOSE_WRONG_TOKEN)
            return False, hello
        last = await asyncio.to_thread(self._last_seq, session)
        await conn.send(message("paired", session, seq, {"headset_id": headset.headset_id,
                                                         "resume_key": headset.resume_key, "studio": STUDIO,
                                                         "last_seq": last}))
        self._publish("headsets", None)
        return headset, hello

    def _last_seq(self, session: str) -> int:
        from sqlalchemy import func
        from sqlmodel import Session, select

        from studio_db.feedback import FeedbackRow
        with Session(self.feedback.engine) as s:
            return s.exec(select(func.max(FeedbackRow.seq)).where(FeedbackRow.session == session)).one() or 0

    async def _writer(self, conn: Connection, headset: Headset, queue: asyncio.Queue) -> None:
        """Applies messages in order; glove events that queued up together are written in one transaction."""
        done = False
        while not done:
            batch = [await queue.get()]
            while not queue.empty():
                batch.append(queue.get_nowait())
            if batch[-1] is None:
                batch.pop()
                done = True
            events = []
            for msg in batch:
                if msg["type"] == "glove_event":
                    if msg["body"]["push"] not in self._pushes:
                        await self._error(conn, headset, "unknown_push",
                                          f"no scene push {msg['body']['push']!r} was sent to this studio", msg["id"])
                    else:
                        events.append(msg)
                else:
                    await self._apply(conn, headset, msg)
            if events:
                await self._store(conn, headset, events)

    async def _store(self, conn: Connection, headset: Headset, events: list[dict]) -> None:
        try:
            fresh = await asyncio.to_thread(self.feedback.add_events, headset.session, events)
        except Exception as e:  # nothing acked: the headset resends
            log.exception("storing glove events failed")
            await self._error(conn, headset, "internal", f"could not store {len(events)} glove events: {e}", None)
            return
        self._publish("feedback", [m for m, new in zip(events, fresh) if new])
        for m, new in zip(events, fresh):
            await self._send_safely(conn, message("ack", headset.session, 0,
                                                  {"of": m["id"], "seq": m["seq"], "duplicate": not new}))

    async def _apply(self, conn: Connection, headset: Headset, msg: dict) -> None:
        kind, body = msg["type"], msg["body"]
        if kind == "ping":
            await self._send_safely(conn, message("pong", headset.session, 0, {"ping": msg["id"]}))
            return
        if kind == "ack":
            progress = self.progress.get(body["of"])
            if progress is not None and not progress.delivered:
                progress.delivered = True
                self._publish("progress", progress)
            return
        if kind in ("hello", "pair"):
            await self._error(conn, headset, "invalid", f"{kind} after pairing: this connection is paired already",
                              msg["id"])
            return
        if kind in ("pong", "error"):
            if kind == "error":
                log.warning("headset %s reported %s: %s", headset.headset_id, body["code"], body["message"])
            return
        duplicate = msg["seq"] in headset.handled
        if not duplicate:
            headset.handled.add(msg["seq"])
            progress = self.progress.get(body.get("push", ""))
            if "push" in body and progress is None and body["push"] not in self._pushes:
                await self._error(conn, headset, "unknown_push", f"no scene push {body['push']!r}", msg["id"])
                return
            if progress is not None:
                if kind == "scene_loaded":
                    progress.loaded = True
                elif kind == "scene_failed":
                    progress.loaded, progress.failure = False, body["reason"]
                elif kind == "plan_step_result":
                    progress.step = max(progress.step, body["index"] + 1)
                    progress.failed_steps += not body["ok"]
                elif kind == "user_decision":
                    progress.decision = body["decision"]
                self._publish("progress", progress)
        await self._send_safely(conn, message("ack", headset.session, 0,
                                              {"of": msg["id"], "seq": msg["seq"], "duplicate": duplicate}))
        if kind == "session_end":
            with self._lock:
                self.headsets.pop(headset.session, None)
            self._publish("headsets", None)
            await conn.ws.close(1000)

    async def _error(self, conn: Connection, headset: Headset | None, code: str, text: str, of: str | None) -> None:
        session = headset.session if headset else ""
        await self._send_safely(conn, message("error", session, 0, {"code": code, "message": text, "of": of,
                                                                   "fatal": False}))

    async def _refuse(self, conn: Connection, msg: dict, code: str, text: str, close_code: int) -> None:
        await self._send_safely(conn, message("error", msg["session"], 0, {"code": code, "message": text,
                                                                          "of": msg["id"], "fatal": True}))
        await conn.ws.close(close_code, text[:120])

    async def _send_safely(self, conn: Connection, msg: dict) -> None:
        try:
            await conn.send(msg)
        except Exception:  # the socket went away; the headset resends what was not acked
            pass


_bridges: "weakref.WeakKeyDictionary[Store, Bridge]" = weakref.WeakKeyDictionary()


def bridge_for(store: Store) -> Bridge:
    """The one bridge of a store: the API server's websocket and the studio's Headset tabs share it."""
    with _registry_lock:
        if store not in _bridges:
            _bridges[store] = Bridge(store)
        return _bridges[store]


_registry_lock = threading.Lock()
