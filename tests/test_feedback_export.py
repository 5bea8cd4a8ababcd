"""`h3ds feedback export`: filters, a clear error for a bad time, and records the `datasets` JSON loader reads."""

import json
import os

import pytest

from app.cli import main
from studio_db import Store
from studio_db.feedback import FeedbackStore


@pytest.fixture
def stored(tmp_path, monkeypatch, pipeline):
    monkeypatch.setenv("H3DS_DATA_DIR", str(tmp_path / "data"))
    monkeypatch.delenv("DATABASE_URL", raising=False)
    store = Store()
    scene = pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0).scene
    sid, _ = store.create_scene("bread", scene, 0, "dfs")
    fb = FeedbackStore(store)
    for session in ("a", "b"):
        fb.add_push(f"push-{session}", session, "headset-1", "stand-in", sid, 1)
        events = [{"id": f"{session}{i}", "seq": i, "ts": 1.7e9 + i, "body": {
            "push": f"push-{session}", "t": i * 0.5, "object_id": "Bread|1", "object_type": "Bread",
            "kind": "select", "hand": "left", "fingers": ["thumb", "index"], "haptic_class": "cold",
            "intensity": 60, "glove_colour": [0.0, 0.35, 1.0]}} for i in range(1, 6)]
        assert fb.add_events(session, events) == [True] * 5
        assert fb.add_events(session, events[:2]) == [False, False]  # a resend is not stored again
    return sid


def test_export_filters_and_datasets_loads_it(stored, tmp_path, capsys):
    out = tmp_path / "fb.jsonl"
    assert main(["feedback", "export", "--format", "jsonl", "--out", str(out)]) == 0
    rows = [json.loads(x) for x in out.read_text().splitlines()]
    assert len(rows) == 10 and {r["session"] for r in rows} == {"a", "b"}
    assert rows[0]["scene_id"] == stored and rows[0]["task_type"] and json.loads(rows[0]["task_graph"])["objects"]
    assert main(["feedback", "export", "--session", "a"]) == 0
    assert len(capsys.readouterr().out.splitlines()) == 5
    assert main(["feedback", "export", "--scene", str(stored + 1)]) == 0
    assert capsys.readouterr().out == ""
    assert main(["feedback", "export", "--until", "2000-01-01"]) == 0
    assert capsys.readouterr().out == ""
    assert main(["feedback", "export", "--since", "last week"]) == 2
    assert "not an ISO 8601 time" in capsys.readouterr().err
    import datasets
    ds = datasets.load_dataset("json", data_files=str(out), split="train", cache_dir=str(tmp_path / "hf"))
    assert ds.num_rows == 10 and ds[0]["fingers"] == ["thumb", "index"] and ds[0]["glove_colour"][2] == 1.0


POSTGRES = os.environ.get("H3DS_TEST_POSTGRES_URL")


@pytest.mark.skipif(not POSTGRES, reason="no PostgreSQL server: .ci/run starts one and sets H3DS_TEST_POSTGRES_URL")
def test_feedback_dedup_and_export_on_postgresql(pipeline):
    import uuid
    store = Store(POSTGRES)
    scene = pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0).scene
    sid, _ = store.create_scene("bread on postgres", scene, 0, "dfs")
    fb = FeedbackStore(store)
    session = uuid.uuid4().hex
    fb.add_push(f"push-{session}", session, "headset-1", "stand-in", sid, 1)
    events = [{"id": f"m{i}", "seq": i, "ts": 1.7e9 + i, "body": {
        "push": f"push-{session}", "t": 0.5, "object_id": "Bread|1", "object_type": "Bread", "kind": "hover",
        "hand": "right", "fingers": ["index"], "haptic_class": "normal", "intensity": 30,
        "glove_colour": [0.0, 0.0, 0.0]}} for i in range(1, 4)]
    assert fb.add_events(session, events) == [True] * 3
    assert fb.add_events(session, events + events[:1]) == [False] * 4
    rows = list(FeedbackStore(Store(POSTGRES)).records(session=session))
    assert [r["seq"] for r in rows] == [1, 2, 3] and rows[0]["scene_id"] == sid
