"""`h3ds scenes`: a folder stored in the studio's database (a real SQLite file) as a scene or its next version with
its edit log, a stored version written back as a folder that `h3ds edit` reads, and bad input refused in one line
with nothing stored."""

import pytest

from app.cli import main
from app.pipeline import generation_of, write_apartment, write_generation
from models.values import Scene
from models.values.apartment import Apartment
from studio_db import Store

BREAD = "Put a chilled bread on the counter"


@pytest.fixture
def db(tmp_path, monkeypatch):
    url = f"sqlite:///{tmp_path / 'studio.db'}"
    monkeypatch.setenv("DATABASE_URL", url)
    return Store(url)


@pytest.fixture(scope="module")
def kitchen(pipeline):
    return pipeline.generate(BREAD, "kitchen", seed=3).scene


def run(args, capsys):
    code = main(args)
    out, err = capsys.readouterr()
    return code, out, err


def test_a_folder_is_stored_with_its_edits_then_as_the_next_version(db, kitchen, tmp_path, capsys):
    folder = tmp_path / "bread"
    write_generation(generation_of(kitchen), folder)
    assert run(["edit", str(folder), "--move", "fridge-0", "2.0", "1.5", "--solver", "dfs"], capsys)[0] == 0
    code, out, _ = run(["scenes", "store", str(folder), "--name", "fridge moved"], capsys)
    assert code == 0 and out.startswith("stored as scene 1, version 1 (1 edit(s))")
    stored = db.scene(1, 1)
    assert stored == Scene.model_validate_json((folder / "scene.json").read_text())
    assert stored.objects != kitchen.objects
    (edit,) = db.edits(1)
    assert (edit["kind"], edit["target"], edit["after"][:2]) == ("move", "fridge-0", [2.0, 1.5])
    assert not (folder / "edits.jsonl").exists() and (folder / "edits-1-v1.jsonl").exists()  # not stored twice
    assert db.versions(1)[0]["seed"] == 3

    code, out, _ = run(["scenes", "store", str(folder), "--name", "again", "--scene", "1"], capsys)
    assert code == 0 and "version 2 (0 edit(s))" in out and len(db.edits(1)) == 1
    code, out, _ = run(["scenes", "list"], capsys)
    assert out.split()[:4] == ["1", "kitchen", "2", "version(s)"]


def test_a_stored_version_comes_back_as_a_folder_that_edit_reads(db, kitchen, tmp_path, capsys):
    scene_id, _ = db.create_scene("bread", kitchen, 3, "plan2place")
    out = tmp_path / "back"
    code, printed, _ = run(["scenes", "export", str(scene_id), "--out", str(out)], capsys)
    assert code == 0 and str(out / "house.json") in printed
    assert Scene.model_validate_json((out / "scene.json").read_text()) == kitchen
    assert run(["edit", str(out), "--move", "fridge-0", "2.0", "1.5", "--solver", "dfs"], capsys)[0] == 0


def test_an_apartment_goes_both_ways(db, pipeline, tmp_path, capsys):
    flat = pipeline.generate_apartment(BREAD, ["kitchen", "bedroom"], seed=2)
    folder = tmp_path / "flat"
    write_apartment(flat, folder)
    assert run(["scenes", "store", str(folder), "--name", "flat"], capsys)[0] == 0
    assert db.scene(1) == flat and db.list_scenes()[0]["room_type"] == "apartment"
    out = tmp_path / "back"
    assert run(["scenes", "export", "1", "--out", str(out)], capsys)[0] == 0
    assert Apartment.model_validate_json((out / "apartment.json").read_text()) == flat


@pytest.mark.parametrize("args,words", [
    (["store", "{folder}", "--name", "x", "--scene", "9"], "--scene: no scene 9"),
    (["store", "{empty}", "--name", "x"], "holds no scene.json or apartment.json"),
    (["export", "9", "--out", "{tmp}/x"], "scene 9"),
    (["store", "{folder}"], "--name"),
])
def test_bad_input_is_one_line_and_stores_nothing(db, kitchen, tmp_path, capsys, args, words):
    folder, empty = tmp_path / "bread", tmp_path / "empty"
    write_generation(generation_of(kitchen), folder)
    empty.mkdir()
    code, _, err = run(["scenes", *(a.format(folder=folder, empty=empty, tmp=tmp_path) for a in args)], capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1 and words in err, err
    assert db.list_scenes() == []


def test_a_bad_edit_log_stores_nothing_and_is_kept(db, kitchen, tmp_path, capsys):
    folder = tmp_path / "bread"
    write_generation(generation_of(kitchen), folder)
    (folder / "edits.jsonl").write_text('{"kind": "move", "target": "fridge-0"}\n[1, 2]\n')
    code, _, err = run(["scenes", "store", str(folder), "--name", "x"], capsys)
    assert code == 2 and "edits.jsonl: line 2: an edit is an object with text kind and target" in err
    assert db.list_scenes() == [] and len((folder / "edits.jsonl").read_text().splitlines()) == 2


def test_a_single_room_is_not_the_next_version_of_an_apartment(db, pipeline, kitchen, tmp_path, capsys):
    db.create_scene("flat", pipeline.generate_apartment(BREAD, ["kitchen", "bedroom"], seed=2), 2, "plan2place")
    folder = tmp_path / "bread"
    write_generation(generation_of(kitchen), folder)
    (folder / "edits.jsonl").write_text('{"kind": "move", "target": "fridge-0"}\n')
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    code, _, err = run(["scenes", "store", str(folder), "--name", "x", "--scene", "1"], capsys)
    assert code == 2 and "--scene:" in err and len(db.versions(1)) == 1
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before  # the log stays, to store elsewhere
