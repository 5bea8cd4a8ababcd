"""The tables: a scene has numbered versions (each the full Scene JSON) and designer edits."""

from __future__ import annotations

from datetime import datetime, timezone

from sqlmodel import Field, SQLModel


def now() -> datetime:
    return datetime.now(timezone.utc)


class SceneRow(SQLModel, table=True):
    __tablename__ = "scene"

    id: int | None = Field(default=None, primary_key=True)
    name: str
    instruction: str
    room_type: str
    created_at: datetime = Field(default_factory=now)


class VersionRow(SQLModel, table=True):
    __tablename__ = "scene_version"

    id: int | None = Field(default=None, primary_key=True)
    scene_id: int = Field(foreign_key="scene.id", index=True)
    number: int
    name: str
    seed: int
    solver: str
    model_versions: str  # JSON: which parser, planner and solver made it
    scene_json: str  # the full Scene value
    created_at: datetime = Field(default_factory=now)


class EditRow(SQLModel, table=True):
    __tablename__ = "designer_edit"

    id: int | None = Field(default=None, primary_key=True)
    scene_id: int = Field(foreign_key="scene.id", index=True)
    version_id: int | None = Field(default=None, foreign_key="scene_version.id")
    kind: str  # move, constraints, task-graph, override (saved despite failed checks), undo, redo
    target: str  # object id or "plan"
    before: str  # JSON
    after: str  # JSON
    created_at: datetime = Field(default_factory=now)
