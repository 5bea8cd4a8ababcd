"""A designer's edits outside the studio: POST /edit and `h3ds edit` give what the pipeline's own edits give, put
an apartment's room back into the house, log the edits as the studio stores them, and refuse edits that do not fit
with a message naming them, changing nothing."""

import json

import pytest
from fastapi.testclient import TestClient

from app.api import create_app
from app.cli import main
from app.pipeline import Pipeline, generation_of, pose_of, room_generation, write_apartment, write_generation
from models.exports.apartment import apartment_house
from models.scene.apartment import house_objects, with_room
from models.scene.carry import carry
from models.values import Scene
from models.values.apartment import Apartment
from studio_db import Store

BREAD = "Put a chilled bread on the counter"
SEED = 3
SOLVER = "dfs"  # the edits are the pipeline's whichever placer re-places; the cheapest one keeps the tests short


@pytest.fixture(scope="module")
def api(tmp_path_factory):
    db = tmp_path_factory.mktemp("edit") / "studio.db"
    return TestClient(create_app(Store(f"sqlite:///{db}"), Pipeline(solver=SOLVER)))


@pytest.fixture(scope="module")
def kitchen(api):
    r = api.post("/generate", json={"instruction": BREAD, "room_type": "kitchen", "seed": SEED, "solver": SOLVER})
    return Scene.model_validate(r.json()["scene"])


@pytest.fixture(scope="module")
def flat(api):
    r = api.post("/generate", json={"instruction": BREAD, "room_type": "apartment", "seed": SEED, "solver": SOLVER,
                                    "rooms": ["kitchen", "living room"]})
    return Apartment.model_validate(r.json()["apartment"])


def edit(api, value, edits, **extra):
    key = "scene" if isinstance(value, Scene) else "apartment"
    return api.post("/edit", json={key: json.loads(value.model_dump_json()), "edits": edits, "solver": SOLVER,
                                   **extra})


def poses(layout) -> dict:
    return {p["id"]: (p["x"], p["z"], p["rotation"]) for p in layout["placements"]}


def test_a_move_puts_one_object_and_logs_it(api, kitchen):
    gen = generation_of(kitchen)
    fridge = gen.layout.placement("fridge-0")
    r = edit(api, kitchen, [{"kind": "move", "object": "fridge-0", "x": 2.0, "z": 1.5, "rotation": 180}])
    assert r.status_code == 200, r.text
    after = poses(r.json()["layout"])
    assert after.pop("fridge-0") == (2.0, 1.5, 180.0)
    assert after == {p.id: (p.x, p.z, p.rotation) for p in gen.layout.placements if p.id != "fridge-0"}
    drawn = next(o for o in r.json()["scene"]["objects"] if o["id"] == "fridge-0")
    assert (drawn["x"], drawn["z"]) == (2.0, 1.5)
    assert r.json()["edits"] == [{"kind": "move", "target": "fridge-0", "before": [fridge.x, fridge.z, fridge.rotation],
                                  "after": [2.0, 1.5, 180.0]}]


def test_a_move_onto_another_object_is_a_finding_naming_both(api, kitchen):
    counter = generation_of(kitchen).layout.placement("countertop-0")
    r = edit(api, kitchen, [{"kind": "move", "object": "fridge-0", "x": counter.x, "z": counter.z}])
    collisions = [f for f in r.json()["findings"] if f["kind"] == "collision"]
    assert any(set(f["objects"]) == {"fridge-0", "countertop-0"} for f in collisions), r.json()["findings"]
    assert next(p for p in r.json()["layout"]["placements"] if p["id"] == "fridge-0")["rotation"] == \
        generation_of(kitchen).layout.placement("fridge-0").rotation  # no rotation given: its own


def test_constraint_edit_and_replace_are_the_pipelines_with_the_scenes_own_seed(api, kitchen):
    pipeline, gen = Pipeline(solver=SOLVER), generation_of(kitchen)
    text = gen.plan.constraints.replace("fridge-0 | edge", "fridge-0 | middle")
    assert text != gen.plan.constraints
    r = edit(api, kitchen, [{"kind": "constraints", "text": text}])
    assert poses(r.json()["layout"]) == poses(json.loads(pipeline.replan(gen, text, SEED).layout.model_dump_json()))
    assert r.json()["plan"]["constraints"] == text
    assert r.json()["edits"][0] == {"kind": "constraints", "target": "plan", "before": gen.plan.constraints,
                                    "after": text}

    moves = [{"kind": "move", "object": "fridge-0", "x": 2.0, "z": 1.5}, {"kind": "replace_around",
                                                                         "objects": ["fridge-0"]}]
    r = edit(api, kitchen, moves)
    moved = pipeline.move(gen, "fridge-0", 2.0, 1.5, gen.layout.placement("fridge-0").rotation, SEED)
    want = pipeline.replace_around(moved, ["fridge-0"], SEED)
    assert poses(r.json()["layout"]) == poses(json.loads(want.layout.model_dump_json()))
    assert [e["kind"] for e in r.json()["edits"]] == ["move", "re-place"]


def test_an_edited_scene_is_stored_reopened_and_edited_again(api, kitchen):
    first = edit(api, kitchen, [{"kind": "move", "object": "fridge-0", "x": 2.0, "z": 1.5}]).json()
    saved = api.post("/scenes", json={"name": "moved", "scene": first["scene"], "seed": SEED, "edits": first["edits"]})
    sid = saved.json()["scene_id"]
    assert api.get(f"/scenes/{sid}").json()["edits"][0]["target"] == "fridge-0"
    stored = Scene.model_validate(api.get(f"/scenes/{sid}/versions/1").json())
    again = edit(api, stored, [{"kind": "move", "object": "fridge-0", "x": 2.5, "z": 1.5}])
    assert again.status_code == 200 and again.json()["edits"][0]["before"][:2] == [2.0, 1.5]


def test_an_apartment_room_is_edited_in_its_frame_and_put_back(api, flat):
    pipeline, room = Pipeline(solver=SOLVER), room_generation(flat, 1)
    sofa = next(p for p in room.layout.placements if p.type == "Sofa")
    r = edit(api, flat, [{"kind": "move", "object": sofa.id, "x": 1.5, "z": 1.5}], room=2)
    assert r.status_code == 200, r.text
    want = with_room(flat, 1, room.plan, pipeline.move(room, sofa.id, 1.5, 1.5, sofa.rotation, SEED).layout, SEED)
    got = Apartment.model_validate(r.json()["apartment"])
    assert got == want and r.json()["house"] == apartment_house(want)
    assert got.layouts[0] == flat.layouts[0]  # the other room as it was
    hr, drawn = flat.floorplan.rooms[1], next(o for o in house_objects(got) if o.id == sofa.id)
    assert (drawn.x, drawn.z) == pytest.approx((hr.x + 1.5, hr.z + 1.5))  # in the house: the room's corner added


@pytest.mark.parametrize("body,field,words", [
    ({"edits": [{"kind": "move", "object": "nope-0", "x": 1, "z": 1}]}, ["edits", 0, "object"], "nope-0"),
    ({"edits": [{"kind": "move", "object": "fridge-0", "x": 40, "z": 1}]}, ["edits", 0], "outside"),
    ({"edits": [{"kind": "replace_around", "objects": ["fridge-0", "ghost-1"]}]}, ["edits", 0, "objects"], "ghost-1"),
    ({"edits": [{"kind": "move", "object": "fridge-0", "x": 1, "z": 1}], "room": 2}, ["room"], "single room"),
    ({"edits": []}, ["edits"], ""),
    ({"edits": [{"kind": "paint", "object": "fridge-0"}]}, ["edits", 0], ""),
    ({"edits": [{"kind": "constraints", "text": "x"}], "solver": "magic"}, ["solver"], "magic"),
])
def test_an_edit_that_does_not_fit_is_a_422_naming_it(api, kitchen, body, field, words):
    r = api.post("/edit", json={"scene": json.loads(kitchen.model_dump_json()), **body})
    assert r.status_code == 422
    detail = r.json()["detail"]
    assert any([str(p) for p in d["loc"][1:len(field) + 1]] == [str(p) for p in field] and words in d["msg"]
               for d in detail), detail


@pytest.mark.parametrize("edits,room,words", [
    ([{"kind": "constraints", "text": ""}], None, "none was given"),  # it names no object: say which room
    ([{"kind": "move", "object": "r9-ghost-0", "x": 1, "z": 1}], None, "none was given"),
    ([{"kind": "move", "object": "SOFA", "x": 1, "z": 1}], 3, "not 3"),
])
def test_an_apartment_edit_names_its_room(api, flat, edits, room, words):
    sofa = next(p for p in flat.layouts[1].placements if p.type == "Sofa")
    edits = [{**e, "object": sofa.id} if e.get("object") == "SOFA" else e for e in edits]
    r = edit(api, flat, edits, **({"room": room} if room else {}))
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "room"]
    assert "rooms 1-2" in r.json()["detail"][0]["msg"] and words in r.json()["detail"][0]["msg"]


def test_an_apartment_edit_without_a_room_is_in_the_room_of_the_object_it_names(api, flat):
    sofa = next(p for p in flat.layouts[1].placements if p.type == "Sofa")
    moves = [{"kind": "move", "object": sofa.id, "x": 1.5, "z": 1.5}]
    assert edit(api, flat, moves).json()["apartment"] == edit(api, flat, moves, room=2).json()["apartment"]


def test_edits_of_several_rooms_in_one_request_each_name_their_room(api, flat):
    """An edit's own `room` switches to that room, the edits before it kept in theirs: the same apartment as one
    request per room."""
    fridge = next(p for p in flat.layouts[0].placements if p.type == "Fridge")
    sofa = next(p for p in flat.layouts[1].placements if p.type == "Sofa")
    to_fridge = {"kind": "move", "object": fridge.id, "x": 1.0, "z": 1.0}
    to_sofa = {"kind": "move", "object": sofa.id, "x": 1.5, "z": 1.5}
    both = edit(api, flat, [{**to_fridge, "room": 1}, {**to_sofa, "room": 2}])
    assert both.status_code == 200, both.text
    first = Apartment.model_validate(edit(api, flat, [to_fridge], room=1).json()["apartment"])
    then = edit(api, first, [to_sofa], room=2).json()["apartment"]
    assert both.json()["apartment"] == then and [e["target"] for e in both.json()["edits"]] == [fridge.id, sofa.id]
    # without a room of its own, an edit is in the room of the one before it: the sofa is not in the kitchen
    r = edit(api, flat, [{**to_fridge, "room": 1}, to_sofa])
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "edits", 1, "object"]


@pytest.mark.parametrize("value,edits,field,words", [
    ("flat", [{"kind": "constraints", "text": "", "room": 3}], ["edits", 0, "room"], "not 3"),
    ("flat", [{"kind": "constraints", "text": "", "room": 1}, {"kind": "constraints", "text": "", "room": 4}],
     ["edits", 1, "room"], "not 4"),
    ("kitchen", [{"kind": "constraints", "text": "", "room": 1}], ["edits", 0, "room"], "single room"),
])
def test_an_edits_room_that_does_not_fit_is_a_422_naming_it(api, kitchen, flat, value, edits, field, words):
    r = edit(api, {"flat": flat, "kitchen": kitchen}[value], edits)
    assert r.status_code == 422
    d = r.json()["detail"][0]
    assert d["loc"][1:] == field and words in d["msg"], d


def test_both_or_neither_value_is_a_422(api, kitchen, flat):
    r = api.post("/edit", json={"edits": [{"kind": "constraints", "text": ""}]})
    assert r.status_code == 422 and "exactly one" in r.text
    both = {"scene": json.loads(kitchen.model_dump_json()), "apartment": json.loads(flat.model_dump_json())}
    r = api.post("/edit", json={**both, "edits": [{"kind": "constraints", "text": ""}]})
    assert r.status_code == 422 and "exactly one" in r.text


def test_the_cli_edits_a_generated_folder_in_place_and_logs_it(kitchen, tmp_path, capsys):
    folder = tmp_path / "bread"
    write_generation(generation_of(kitchen), folder)
    assert main(["edit", str(folder), "--move", "fridge-0", "2.0", "1.5", "90", "--solver", SOLVER]) == 0
    layout = json.loads((folder / "layout.json").read_text())
    assert poses(layout)["fridge-0"] == (2.0, 1.5, 90.0)
    house = json.loads((folder / "house.json").read_text())
    assert any(o["id"].startswith("Fridge") and o["position"]["x"] == pytest.approx(2.0, abs=1e-3)
               for o in house["objects"])
    assert Scene.model_validate_json((folder / "scene.json").read_text()).objects != kitchen.objects
    capsys.readouterr()

    copy = tmp_path / "copy"
    assert main(["edit", str(folder), "--replace-around", "fridge-0", "--out", str(copy), "--solver", SOLVER]) == 0
    rows = [json.loads(line) for line in (copy / "edits.jsonl").read_text().splitlines()]
    assert [r["kind"] for r in rows] == ["move", "re-place"] and rows[0]["after"] == [2.0, 1.5, 90.0]
    assert len((folder / "edits.jsonl").read_text().splitlines()) == 1  # the source folder's log as it was


@pytest.mark.parametrize("args,words", [
    (["--move", "ghost-0", "1", "1"], "--move: ghost-0 is not an object"),
    (["--move", "fridge-0", "1"], "--move takes ID X Z [ROTATION], not 2"),
    (["--move", "fridge-0", "one", "1"], "--move: X, Z and ROTATION are numbers"),
    (["--room", "2", "--replace-around", "fridge-0"], "--room: scene scene-3 is a single room"),
    (["--constraints", "/nonexistent/c.txt"], "--constraints: cannot read"),
    (["--edits", "EDITS:[]"], "List should have at least 1 item"),
    (["--edits", 'EDITS:[{"kind": "paint"}]'], "--edits [0]: Input tag 'paint'"),
    (["--edits", 'EDITS:[{"kind": "move", "object": "fridge-0", "x": "far", "z": 1}]'], "--edits [0].move.x: Input"),
    (["--edits", 'EDITS:[{"kind": "constraints", "text": ""}, {"kind": "move", "object": "ghost-0", "x": 1, "z": 1}]'],
     "--edits [1]: ghost-0 is not an object"),
    (["--edits", 'EDITS:[{"kind": "constraints", "text": "", "room": 2}]'], "--edits [0]: scene scene-3 is a single"),
])
def test_a_cli_edit_that_does_not_fit_exits_2_and_changes_nothing(kitchen, tmp_path, capsys, args, words):
    folder = tmp_path / "bread"
    write_generation(generation_of(kitchen), folder)
    if args[-1].startswith("EDITS:"):  # an edits file beside the folder
        (tmp_path / "edits.json").write_text(args[-1].removeprefix("EDITS:"))
        args = [*args[:-1], str(tmp_path / "edits.json")]
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    assert main(["edit", str(folder), *args]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and words in err, err
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before


def test_the_cli_makes_several_edits_from_a_file_as_post_edit_does(api, flat, tmp_path, capsys):
    """`h3ds edit DIR --edits FILE`: POST /edit's edits list, each naming its room, in one run; the same apartment and
    log rows as the API's answer."""
    folder = tmp_path / "flat"
    write_apartment(flat, folder)
    fridge = next(p for p in flat.layouts[0].placements if p.type == "Fridge")
    sofa = next(p for p in flat.layouts[1].placements if p.type == "Sofa")
    edits = [{"kind": "move", "object": fridge.id, "x": 1.0, "z": 1.0, "room": 1},
             {"kind": "move", "object": sofa.id, "x": 1.5, "z": 1.5, "room": 2}]
    (tmp_path / "edits.json").write_text(json.dumps(edits))
    assert main(["edit", str(folder), "--edits", str(tmp_path / "edits.json"), "--solver", SOLVER]) == 0
    answer = edit(api, flat, edits).json()
    assert Apartment.model_validate_json((folder / "apartment.json").read_text()) == \
        Apartment.model_validate(answer["apartment"])
    rows = [json.loads(line) for line in (folder / "edits.jsonl").read_text().splitlines()]
    assert rows == answer["edits"]


def test_the_cli_edits_an_apartment_room_and_a_folder_without_a_scene_is_refused(flat, tmp_path, capsys):
    folder = tmp_path / "flat"
    write_apartment(flat, folder)
    text = flat.plans[1].constraints + "\n"
    constraints = tmp_path / "c.txt"
    constraints.write_text(text.replace(" | edge", " | middle", 1))
    assert main(["edit", str(folder), "--room", "2", "--constraints", str(constraints), "--solver", SOLVER]) == 0
    edited = Apartment.model_validate_json((folder / "apartment.json").read_text())
    assert edited.plans[1].constraints == constraints.read_text().strip("\n") and edited.plans[0] == flat.plans[0]
    room = next(folder.glob("rooms/2-*"))
    assert json.loads((room / "plan.json").read_text())["constraints"] == edited.plans[1].constraints
    capsys.readouterr()
    assert main(["edit", str(tmp_path), "--move", "a", "1", "1"]) == 2
    assert "holds no scene.json or apartment.json" in capsys.readouterr().err


def test_an_apartment_object_is_carried_into_another_room_after_the_edits_before_it(api, flat):
    pipeline, kitchen = Pipeline(solver=SOLVER), room_generation(flat, 0)
    fridge = next(p for p in kitchen.layout.placements if p.type == "Fridge")
    table = next(o for o in kitchen.plan.objects if o.holds)
    r = edit(api, flat, [{"kind": "move", "object": fridge.id, "x": 1.0, "z": 1.0},
                         {"kind": "move", "object": table.id, "x": 2.0, "z": 2.5, "to_room": 2}], room=1)
    assert r.status_code == 200, r.text
    moved = with_room(flat, 0, kitchen.plan, pipeline.move(kitchen, fridge.id, 1.0, 1.0, fridge.rotation, SEED).layout,
                      SEED)
    want, new_id = carry(moved, table.id, 1, 2.0, 2.5, next(p for p in kitchen.layout.placements
                                                             if p.id == table.id).rotation, SEED)
    assert Apartment.model_validate(r.json()["apartment"]) == want and new_id.startswith("r2-")
    follow = edit(api, flat, [{"kind": "move", "object": table.id, "x": 2.0, "z": 2.5, "to_room": 2},
                              {"kind": "replace_around", "objects": [new_id]}], room=1)  # then in the living room
    assert follow.status_code == 200, follow.text
    around = pipeline.replace_around(room_generation(want, 1), [new_id], SEED)
    assert Apartment.model_validate(follow.json()["apartment"]).layouts[1].placements == around.layout.placements
    assert r.json()["edits"][1] == {"kind": "carry", "target": table.id,
                                    "before": {"room": 1, "pose": list(pose_of(kitchen.layout.placement(table.id)))},
                                    "after": {"room": 2, "id": new_id, "pose": [2.0, 2.5, want.layouts[1].placement(
                                        new_id).rotation]}}


@pytest.mark.parametrize("move,field,words", [
    ({"to_room": 1}, ["edits", 0, "to_room"], "other than room 1"),
    ({"to_room": 5}, ["edits", 0, "to_room"], "not 5"),
    ({"to_room": 2, "x": 40}, ["edits", 0], "outside"),
])
def test_a_carry_that_does_not_fit_is_a_422_naming_it(api, flat, move, field, words):
    table = next(o for o in flat.plans[0].objects if o.holds)
    r = edit(api, flat, [{"kind": "move", "object": table.id, "x": 1.0, "z": 1.0, **move}], room=1)
    assert r.status_code == 422
    d = r.json()["detail"][0]
    assert d["loc"][1:] == field and words in d["msg"], d


def test_a_single_room_has_no_room_to_carry_to(api, kitchen):
    r = edit(api, kitchen, [{"kind": "move", "object": "fridge-0", "x": 1.0, "z": 1.0, "to_room": 2}])
    assert r.status_code == 422 and "single room" in r.json()["detail"][0]["msg"]


def test_the_cli_carries_an_object_into_another_room(flat, tmp_path, capsys):
    folder = tmp_path / "flat"
    write_apartment(flat, folder)
    table = next(o for o in flat.plans[0].objects if o.holds)
    assert main(["edit", str(folder), "--move", table.id, "2.0", "2.5", "--to-room", "2"]) == 0  # its room: 1
    edited = Apartment.model_validate_json((folder / "apartment.json").read_text())
    new_id = "r2-" + table.id.split("-", 1)[1]
    assert any(p["id"] == new_id for p in json.loads(next(folder.glob("rooms/2-*/layout.json")).read_text())[
        "placements"])
    assert edited.plan.assignment["Bread"] == "room|2"
    capsys.readouterr()
    assert main(["edit", str(folder), "--room", "1", "--replace-around", "r1-fridge-0", "--to-room", "2"]) == 2
    assert "--to-room goes with --move" in capsys.readouterr().err
