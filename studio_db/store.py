"""The store: every write is one transaction, so a failed write leaves what was stored before intact.

A stored scene is a single room (a Scene) or an apartment (an Apartment, stored under room type
"apartment"); all versions of one stored scene are of the same kind.

SQLite (the default) lives in the user's data directory with write-ahead logging; set `DATABASE_URL`
(for example `postgresql+psycopg://user@host/db`) to use PostgreSQL instead.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from sqlalchemy import event, func
from sqlmodel import Session, SQLModel, create_engine, select

from models.values import Scene
from models.values.apartment import APARTMENT, Apartment
from models.values.edit import Edit
from studio_db.tables import EditRow, SceneRow, VersionRow

Stored = Scene | Apartment


class NotFound(LookupError):
    pass


class WrongKind(ValueError):
    """A single room given as the next version of an apartment, or the other way round."""


def _room_type_of(value: Stored) -> str:
    return APARTMENT if isinstance(value, Apartment) else value.room.type


def _provenance(value: Stored) -> dict[str, str]:
    """stage -> method: which parser, planners and solver made it (an apartment's floorplan and rooms)."""
    if isinstance(value, Scene):
        return {p.stage: p.method for p in value.provenance}
    found = [value.floorplan.provenance] if value.floorplan.provenance else []
    return {p.stage: p.method for p in found + [p for s in value.scenes for p in s.provenance]}


def data_dir() -> Path:
    base = os.environ.get("H3DS_DATA_DIR") or os.path.join(
        os.environ.get("XDG_DATA_HOME") or os.path.expanduser("~/.local/share"), "h3ds-studio")
    return Path(base)


def default_database_url() -> str:
    return os.environ.get("DATABASE_URL") or f"sqlite:///{data_dir() / 'studio.db'}"


class Store:
    def __init__(self, url: str | None = None):
        self.url = url or default_database_url()
        if self.url.startswith("sqlite:///"):
            Path(self.url.removeprefix("sqlite:///")).parent.mkdir(parents=True, exist_ok=True)
            self.engine = create_engine(self.url, connect_args={"check_same_thread": False})
            event.listen(self.engine, "connect", _sqlite_pragmas)
        else:
            self.engine = create_engine(self.url, pool_pre_ping=True)
        SQLModel.metadata.create_all(self.engine)

    @property
    def location(self) -> str:
        return self.url.removeprefix("sqlite:///") if self.url.startswith("sqlite:///") else self.url

    # ---- writes (one transaction each) ------------------------------------------------------------

    def create_scene(self, name: str, scene: Stored, seed: int, solver: str, edits: list[Edit] = ()) -> tuple[int, int]:
        """A new scene (a single room or an apartment) with its first version; returns (scene id, version number)."""
        graph = scene.task_graph
        with Session(self.engine) as s, s.begin():
            row = SceneRow(name=name, instruction=graph.instruction if graph else "", room_type=_room_type_of(scene))
            s.add(row)
            s.flush()
            self._add_version(s, row.id, name, scene, seed, solver, edits)
            return row.id, 1

    def add_version(self, scene_id: int, name: str, scene: Stored, seed: int, solver: str,
                    edits: list[Edit] = ()) -> int:
        """The next version of a stored scene, of the same kind (WrongKind otherwise)."""
        with Session(self.engine) as s, s.begin():
            row = s.get(SceneRow, scene_id)
            if row is None:
                raise NotFound(f"no scene {scene_id}")
            if (row.room_type == APARTMENT) != isinstance(scene, Apartment):
                raise WrongKind(f"scene {scene_id} is {_kind(row.room_type == APARTMENT)}; its next version "
                                f"cannot be {_kind(isinstance(scene, Apartment))}")
            return self._add_version(s, scene_id, name, scene, seed, solver, edits)

    def _add_version(self, s: Session, scene_id: int, name: str, scene: Stored, seed: int, solver: str,
                     edits) -> int:
        number = (s.exec(select(func.max(VersionRow.number)).where(VersionRow.scene_id == scene_id)).one() or 0) + 1
        version = VersionRow(scene_id=scene_id, number=number, name=name, seed=seed, solver=solver,
                             model_versions=json.dumps(_provenance(scene)), scene_json=scene.model_dump_json())
        s.add(version)
        s.flush()
        for e in edits:
            s.add(EditRow(scene_id=scene_id, version_id=version.id, kind=e.kind, target=e.target,
                          before=json.dumps(e.before), after=json.dumps(e.after)))
        return number

    # ---- reads ------------------------------------------------------------------------------------

    def list_scenes(self) -> list[dict]:
        with Session(self.engine) as s:
            rows = s.exec(select(SceneRow).order_by(SceneRow.id.desc())).all()
            counts = dict(s.exec(select(VersionRow.scene_id, func.count()).group_by(VersionRow.scene_id)).all())
            return [{"id": r.id, "name": r.name, "instruction": r.instruction, "room_type": r.room_type,
                     "created_at": r.created_at.isoformat(), "versions": counts.get(r.id, 0)} for r in rows]

    def versions(self, scene_id: int) -> list[dict]:
        with Session(self.engine) as s:
            if s.get(SceneRow, scene_id) is None:
                raise NotFound(f"no scene {scene_id}")
            rows = s.exec(select(VersionRow).where(VersionRow.scene_id == scene_id).order_by(VersionRow.number)).all()
            return [{"number": r.number, "name": r.name, "seed": r.seed, "solver": r.solver,
                     "model_versions": json.loads(r.model_versions), "created_at": r.created_at.isoformat()}
                    for r in rows]

    def scene(self, scene_id: int, number: int | None = None) -> Stored:
        """A stored version (the latest when `number` is None): a Scene, or an Apartment for an apartment."""
        with Session(self.engine) as s:
            q = (select(VersionRow.scene_json, SceneRow.room_type).join(SceneRow, VersionRow.scene_id == SceneRow.id)
                 .where(VersionRow.scene_id == scene_id))
            q = q.where(VersionRow.number == number) if number is not None else q.order_by(VersionRow.number.desc())
            row = s.exec(q).first()
            if row is None:
                raise NotFound(f"no version {number if number is not None else '(any)'} of scene {scene_id}")
            kind = Apartment if row.room_type == APARTMENT else Scene
            return kind.model_validate_json(row.scene_json)

    def edits(self, scene_id: int) -> list[dict]:
        with Session(self.engine) as s:
            rows = s.exec(select(EditRow).where(EditRow.scene_id == scene_id).order_by(EditRow.id)).all()
            return [{"kind": r.kind, "target": r.target, "before": json.loads(r.before), "after": json.loads(r.after),
                     "version_id": r.version_id, "created_at": r.created_at.isoformat()} for r in rows]


def _kind(apartment: bool) -> str:
    return "an apartment" if apartment else "a single room"


def _sqlite_pragmas(conn, _record) -> None:
    cur = conn.cursor()
    cur.execute("PRAGMA journal_mode=WAL")
    cur.execute("PRAGMA foreign_keys=ON")
    cur.execute("PRAGMA synchronous=NORMAL")
    cur.close()
