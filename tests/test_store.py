"""Storage on a real SQLite file: persistence across reopen, and failed writes that change nothing."""

import os

import pytest

from models.values.edit import Edit
from studio_db import NotFound, Store


@pytest.fixture(scope="module")
def scene(pipeline):
    return pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0).scene


def test_versions_survive_a_reopen_and_use_wal(tmp_path, scene):
    url = f"sqlite:///{tmp_path / 'db.sqlite'}"
    store = Store(url)
    sid, _ = store.create_scene("bread", scene, 0, "dfs", [Edit("move", "fridge-0", [0, 0], [1, 1])])
    store.add_version(sid, "bread 2", scene, 1, "dfs")
    reopened = Store(url)
    assert [v["number"] for v in reopened.versions(sid)] == [1, 2]
    assert reopened.scene(sid, 1) == scene and reopened.scene(sid).id == scene.id
    assert reopened.edits(sid)[0]["after"] == [1, 1]
    with reopened.engine.connect() as c:
        assert c.exec_driver_sql("PRAGMA journal_mode").scalar() == "wal"


def test_a_failed_write_leaves_the_previous_version_intact(tmp_path, scene):
    store = Store(f"sqlite:///{tmp_path / 'db.sqlite'}")
    sid, _ = store.create_scene("bread", scene, 0, "dfs")
    with pytest.raises(TypeError):  # an edit whose payload cannot be stored aborts the whole version
        store.add_version(sid, "broken", scene, 0, "dfs", [Edit("move", "x", object(), None)])
    assert [v["number"] for v in store.versions(sid)] == [1]
    assert store.scene(sid) == scene and store.edits(sid) == []


def test_unknown_scene(tmp_path, scene):
    store = Store(f"sqlite:///{tmp_path / 'db.sqlite'}")
    with pytest.raises(NotFound):
        store.add_version(7, "nope", scene, 0, "dfs")
    with pytest.raises(NotFound):
        store.scene(7)


POSTGRES = os.environ.get("H3DS_TEST_POSTGRES_URL")


@pytest.mark.skipif(not POSTGRES, reason="no PostgreSQL server: .ci/run starts one and sets H3DS_TEST_POSTGRES_URL")
def test_postgresql_through_database_url(scene, monkeypatch):
    from studio_db import default_database_url
    monkeypatch.setenv("DATABASE_URL", POSTGRES)
    assert default_database_url() == POSTGRES
    store = Store()
    sid, _ = store.create_scene("bread on postgres", scene, 0, "dfs", [Edit("move", "fridge-0", [0, 0], [1, 1])])
    reopened = Store()
    assert reopened.scene(sid) == scene and reopened.edits(sid)[0]["target"] == "fridge-0"
    with pytest.raises(TypeError):
        reopened.add_version(sid, "broken", scene, 0, "dfs", [Edit("move", "x", object(), None)])
    assert [v["number"] for v in reopened.versions(sid)] == [1]


@pytest.fixture(scope="module")
def apartment(pipeline):
    return pipeline.generate_apartment("Put a chilled bread on the counter", ["kitchen", "living room"], seed=4)


def test_apartments_are_stored_as_versions_beside_single_rooms(tmp_path, scene, apartment):
    from models.values.apartment import Apartment
    url = f"sqlite:///{tmp_path / 'db.sqlite'}"
    store = Store(url)
    room_id, _ = store.create_scene("bread", scene, 0, "dfs")  # a database that already holds a single room
    flat_id, number = store.create_scene("flat", apartment, 4, "dfs")
    assert number == 1 and store.add_version(flat_id, "flat again", apartment, 5, "dfs") == 2
    reopened = Store(url)
    stored = reopened.scene(flat_id, 1)
    assert isinstance(stored, Apartment) and stored == apartment
    assert reopened.scene(room_id) == scene
    listed = {s["id"]: s for s in reopened.list_scenes()}
    assert listed[flat_id]["room_type"] == "apartment" and listed[flat_id]["versions"] == 2
    assert listed[room_id]["room_type"] == "kitchen"
    assert [v["seed"] for v in reopened.versions(flat_id)] == [4, 5]
    assert {"floorplan", "room_plan", "layout"} <= set(reopened.versions(flat_id)[0]["model_versions"])


def test_a_version_of_the_other_kind_is_refused_and_changes_nothing(tmp_path, scene, apartment):
    from studio_db.store import WrongKind
    store = Store(f"sqlite:///{tmp_path / 'db.sqlite'}")
    room_id, _ = store.create_scene("bread", scene, 0, "dfs")
    flat_id, _ = store.create_scene("flat", apartment, 4, "dfs")
    with pytest.raises(WrongKind, match="is a single room; its next version cannot be an apartment"):
        store.add_version(room_id, "flat", apartment, 0, "dfs")
    with pytest.raises(WrongKind, match="is an apartment"):
        store.add_version(flat_id, "bread", scene, 0, "dfs")
    assert [len(store.versions(i)) for i in (room_id, flat_id)] == [1, 1]
    assert store.scene(flat_id) == apartment
