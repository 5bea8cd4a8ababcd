"""Headset feedback: scene pushes and the glove events that came back, tied to the stored scene version.

A glove event is stored once per (session, seq) — the unique key makes a resent event a no-op — and
every write is one transaction, so the caller acks only what has committed.
"""

from __future__ import annotations

import json
import threading
from datetime import datetime, timezone
from typing import Iterator

from sqlalchemy import UniqueConstraint, insert
from sqlmodel import Field, Session, SQLModel, select

from studio_db.store import NotFound, Store
from studio_db.tables import SceneRow, VersionRow, now


class HeadsetPushRow(SQLModel, table=True):
    """One scene version sent to one headset session."""

    __tablename__ = "headset_push"

    id: str = Field(primary_key=True)  # the push id carried by every message about it
    session: str = Field(index=True)
    headset_id: str
    device: str
    scene_id: int = Field(foreign_key="scene.id", index=True)
    version_id: int = Field(foreign_key="scene_version.id")
    created_at: datetime = Field(default_factory=now)


class FeedbackRow(SQLModel, table=True):
    """One glove event as the headset sent it."""

    __tablename__ = "glove_feedback"
    __table_args__ = (UniqueConstraint("session", "seq", name="uq_feedback_session_seq"),)

    id: int | None = Field(default=None, primary_key=True)
    session: str = Field(index=True)
    seq: int
    message_id: str
    push_id: str = Field(foreign_key="headset_push.id", index=True)
    sent_at: datetime  # the headset's clock (envelope ts)
    received_at: datetime = Field(default_factory=now, index=True)
    t: float
    object_id: str
    object_type: str
    kind: str
    hand: str
    fingers: str  # JSON list
    haptic_class: str
    intensity: int
    glove_colour: str  # JSON [r, g, b]


class FeedbackStore:
    """Feedback reads and writes over a Store's database."""

    def __init__(self, store: Store):
        self.store = store
        self.engine = store.engine
        SQLModel.metadata.create_all(self.engine, tables=[HeadsetPushRow.__table__, FeedbackRow.__table__])
        self._write = threading.Lock()  # one writer: the duplicate check and the insert see the same rows

    def add_push(self, push_id: str, session: str, headset_id: str, device: str, scene_id: int,
                 number: int) -> None:
        with Session(self.engine) as s, s.begin():
            version = s.exec(select(VersionRow).where(VersionRow.scene_id == scene_id,
                                                      VersionRow.number == number)).first()
            if version is None:
                raise NotFound(f"no version {number} of scene {scene_id}")
            s.add(HeadsetPushRow(id=push_id, session=session, headset_id=headset_id, device=device,
                                 scene_id=scene_id, version_id=version.id))

    def push_ids(self) -> set[str]:
        with Session(self.engine) as s:
            return set(s.exec(select(HeadsetPushRow.id)).all())

    def add_events(self, session: str, messages: list[dict]) -> list[bool]:
        """Store glove_event messages of one session in one transaction; returns, per message, whether it
        was new (False: that (session, seq) was stored before, or earlier in this batch)."""
        with self._write, Session(self.engine) as s, s.begin():
            seqs = [m["seq"] for m in messages]
            seen = set(s.exec(select(FeedbackRow.seq).where(FeedbackRow.session == session,
                                                            FeedbackRow.seq.in_(seqs))).all())
            fresh, rows = [], []
            for m in messages:
                new = m["seq"] not in seen
                fresh.append(new)
                if not new:
                    continue
                seen.add(m["seq"])
                b = m["body"]
                rows.append({"session": session, "seq": m["seq"], "message_id": m["id"], "push_id": b["push"],
                             "sent_at": datetime.fromtimestamp(m["ts"], timezone.utc), "received_at": now(),
                             "t": b["t"], "object_id": b["object_id"], "object_type": b["object_type"],
                             "kind": b["kind"], "hand": b["hand"], "fingers": json.dumps(b["fingers"]),
                             "haptic_class": b["haptic_class"], "intensity": b["intensity"],
                             "glove_colour": json.dumps(b["glove_colour"])})
            if rows:  # one executemany: the ORM's per-object bookkeeping costs more than the write
                s.execute(insert(FeedbackRow.__table__), rows)
            return fresh

    def count(self, session: str | None = None) -> int:
        from sqlalchemy import func
        with Session(self.engine) as s:
            q = select(func.count()).select_from(FeedbackRow)
            return s.exec(q.where(FeedbackRow.session == session) if session else q).one()

    def records(self, since: datetime | None = None, until: datetime | None = None, scene_id: int | None = None,
                session: str | None = None) -> Iterator[dict]:
        """One export record per stored glove event, joined with its scene version and task graph
        (fields documented in the README, "Feedback export"), oldest first."""
        with Session(self.engine) as s:
            q = (select(FeedbackRow, HeadsetPushRow, VersionRow, SceneRow)
                 .join(HeadsetPushRow, FeedbackRow.push_id == HeadsetPushRow.id)
                 .join(VersionRow, HeadsetPushRow.version_id == VersionRow.id)
                 .join(SceneRow, HeadsetPushRow.scene_id == SceneRow.id))
            if since is not None:
                q = q.where(FeedbackRow.received_at >= since)
            if until is not None:
                q = q.where(FeedbackRow.received_at < until)
            if scene_id is not None:
                q = q.where(HeadsetPushRow.scene_id == scene_id)
            if session is not None:
                q = q.where(FeedbackRow.session == session)
            graphs: dict[int, tuple[str, str, str]] = {}
            for f, p, v, sc in s.exec(q.order_by(FeedbackRow.id)):
                if v.id not in graphs:
                    graph = json.loads(v.scene_json).get("task_graph") or {}
                    graphs[v.id] = (json.dumps(graph, sort_keys=True), graph.get("task_type", ""),
                                    v.model_versions)
                graph_json, task_type, model_versions = graphs[v.id]
                yield {
                    "event_id": f"{f.session}:{f.seq}", "session": f.session, "seq": f.seq,
                    "message_id": f.message_id, "headset_id": p.headset_id, "device": p.device,
                    "push_id": p.id, "scene_id": sc.id, "scene_name": sc.name, "scene_version": v.number,
                    "instruction": sc.instruction, "room_type": sc.room_type, "task_type": task_type,
                    "task_graph": graph_json, "model_versions": model_versions,
                    "sent_at": _iso(f.sent_at), "received_at": _iso(f.received_at), "t": f.t,
                    "object_id": f.object_id, "object_type": f.object_type, "kind": f.kind, "hand": f.hand,
                    "fingers": json.loads(f.fingers), "haptic_class": f.haptic_class, "intensity": f.intensity,
                    "glove_colour": json.loads(f.glove_colour),
                }


def _iso(d: datetime) -> str:
    return (d if d.tzinfo else d.replace(tzinfo=timezone.utc)).isoformat()
