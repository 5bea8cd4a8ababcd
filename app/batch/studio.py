"""`h3ds batch generate --studio`: every finished scene also in the studio's database, for its Scenes tab.

A scene is stored by its worker, before the scene's folder is published, under the name
`<batch folder>/<id> (<first 8 hex of the line's digest>)`; a name already stored is not stored again.
So a worker killed between the two steps leaves a stored scene that its retry skips, a re-run stores
only what is missing, and a changed line is a new name. The database is the studio's: DATABASE_URL
(PostgreSQL when workers on several machines write) or its SQLite file.
"""

from __future__ import annotations

_stores: dict = {}  # one Store (engine, connection pool) per database per worker process


def _store(url: str):
    if url not in _stores:
        from studio_db.store import Store
        _stores[url] = Store(url)
    return _stores[url]


def studio_name(batch: str, key: str, digest: str) -> str:
    return f"{batch}/{key} ({digest[:8]})"


def _names(url: str, where) -> set[str]:
    """The stored scene names that `where(name column)` selects."""
    from sqlmodel import Session, select

    from studio_db.tables import SceneRow

    with Session(_store(url).engine) as s:
        return set(s.exec(select(SceneRow.name).where(where(SceneRow.name))).all())


def stored_names(url: str, batch: str) -> set[str]:
    """The names of this batch's scenes already in the database."""
    return _names(url, lambda name: name.startswith(f"{batch}/", autoescape=True))


def store_scene(url: str, name: str, gen, seed: int, solver: str) -> None:
    """One generated scene as a new studio scene, unless one of that name is stored already."""
    if not _names(url, lambda column: column == name):
        _store(url).create_scene(name, gen.scene, seed, solver)
