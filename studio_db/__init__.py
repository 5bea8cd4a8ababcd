"""Storage of scenes, their versions and designers' edits (SQLModel; SQLite by default, PostgreSQL by URL).

It knows only the value types of `models.values`.
"""

from studio_db.store import NotFound, Store, default_database_url

__all__ = ["NotFound", "Store", "default_database_url"]
