"""The HTTP service against a real SQLite file, with a restart of the app between write and read."""

import pytest
from fastapi.testclient import TestClient

from app.api import create_app
from studio_db import Store


@pytest.fixture
def db_url(tmp_path):
    return f"sqlite:///{tmp_path / 'studio.db'}"


def client(db_url):
    return TestClient(create_app(Store(db_url)))


def test_generate_accept_restart_read_export(db_url):
    api = client(db_url)
    assert api.get("/health").json()["status"] == "ok"
    gen = api.post("/generate", json={"instruction": "Put a chilled bread on the counter", "room_type": "Kitchen",
                                      "seed": 2})
    assert gen.status_code == 200
    scene = gen.json()["scene"]
    saved = api.post("/scenes", json={"name": "bread v1", "scene": scene, "seed": 2, "solver": "dfs",
                                      "edits": [{"kind": "move", "target": "fridge-0", "before": [1, 2], "after": [2, 2]}]})
    assert saved.status_code == 201 and saved.json()["version"] == 1
    sid = saved.json()["scene_id"]
    assert api.post(f"/scenes/{sid}/versions", json={"name": "bread v2", "scene": scene}).json()["version"] == 2

    again = client(db_url)  # a new app on the same file: nothing stored is lost
    listed = again.get("/scenes").json()
    assert listed[0]["id"] == sid and listed[0]["versions"] == 2
    detail = again.get(f"/scenes/{sid}").json()
    assert [v["number"] for v in detail["versions"]] == [1, 2] and detail["edits"][0]["target"] == "fridge-0"
    assert again.get(f"/scenes/{sid}/versions/1").json()["id"] == scene["id"]
    house = again.get(f"/scenes/{sid}/versions/2/house.json").json()
    assert house["metadata"]["schema"] == "1.0.0"
    glb = again.get(f"/scenes/{sid}/versions/2/scene.glb")
    assert glb.content[:4] == b"glTF"
    assert again.get(f"/scenes/{sid}/versions/2/layout.json").json()["placements"]


@pytest.mark.parametrize("body,field", [
    ({"instruction": "", "room_type": "kitchen"}, "instruction"),
    ({"instruction": "x" * 2000, "room_type": "kitchen"}, "instruction"),
    ({"instruction": "Put a mug in the sink", "room_type": "spaceship"}, "room_type"),
    ({"instruction": "Put a mug in the sink", "room_type": "kitchen", "seed": -1}, "seed"),
    ({"instruction": "Put a mug in the sink", "room_type": "kitchen", "solver": "magic"}, "solver"),
    ({"room_type": "kitchen"}, "instruction"),
])
def test_bad_requests_are_422_naming_the_field(db_url, body, field):
    r = client(db_url).post("/generate", json=body)
    assert r.status_code == 422
    assert any(field in [str(p) for p in d["loc"]] for d in r.json()["detail"])


def test_bad_accept_is_422_and_stores_nothing(db_url):
    api = client(db_url)
    r = api.post("/scenes", json={"name": "", "scene": {"id": "x"}})
    assert r.status_code == 422 and {"name", "scene"} <= {d["loc"][1] for d in r.json()["detail"]}
    assert api.get("/scenes").json() == []


def test_missing_things_are_404(db_url):
    api = client(db_url)
    assert api.get("/scenes/99").status_code == 404
    assert api.get("/scenes/99/versions/1/house.json").status_code == 404


def test_openapi_documents_every_route(db_url):
    paths = client(db_url).get("/openapi.json").json()["paths"]
    assert {"/generate", "/place", "/place/steps", "/scenes", "/scenes/{scene_id}/versions",
            "/scenes/{scene_id}/versions/{number}/scene.glb",
            "/health"} <= set(paths)


def test_apartment_accept_restart_read_export(db_url):
    api = client(db_url)
    gen = api.post("/generate", json={"instruction": "Put a chilled bread on the counter", "room_type": "apartment",
                                      "rooms": ["kitchen", "bedroom"], "seed": 4}).json()
    saved = api.post("/scenes", json={"name": "flat", "apartment": gen["apartment"], "seed": 4})
    assert saved.status_code == 201 and saved.json()["version"] == 1
    sid = saved.json()["scene_id"]
    assert api.post(f"/scenes/{sid}/versions", json={"name": "flat 2", "apartment": gen["apartment"]}).json() == \
        {"scene_id": sid, "version": 2}
    single = api.post("/generate", json={"instruction": "Put a chilled bread on the counter", "room_type": "kitchen"})
    wrong = api.post(f"/scenes/{sid}/versions", json={"name": "a room", "scene": single.json()["scene"]})
    assert wrong.status_code == 409 and "is an apartment" in wrong.json()["detail"]
    both = api.post("/scenes", json={"name": "both", "scene": single.json()["scene"], "apartment": gen["apartment"]})
    assert both.status_code == 422 and "exactly one of scene" in both.text

    again = client(db_url)
    listed = again.get("/scenes").json()
    assert listed[0]["id"] == sid and listed[0]["room_type"] == "apartment" and listed[0]["versions"] == 2
    stored = again.get(f"/scenes/{sid}/versions/2").json()
    assert [hr["room"]["type"] for hr in stored["plan"]["floorplan"]["rooms"]] == ["kitchen", "bedroom"]
    house = again.get(f"/scenes/{sid}/versions/2/house.json").json()
    assert house == gen["house"] and [r["id"] for r in house["rooms"]] == ["room|1", "room|2"]
    assert again.get(f"/scenes/{sid}/versions/1/scene.glb").content[:4] == b"glTF"
    layout = again.get(f"/scenes/{sid}/versions/1/layout.json")
    assert layout.status_code == 409 and "one per room" in layout.json()["detail"]


@pytest.mark.parametrize("extra", [{}, {"scene": {"id": "x"}, "apartment": {"id": "y"}}])
def test_accept_needs_exactly_one_of_scene_and_apartment(db_url, extra):
    api = client(db_url)
    r = api.post("/scenes", json={"name": "nothing or both", **extra})
    assert r.status_code == 422 and api.get("/scenes").json() == []
    if not extra:
        assert "exactly one of scene (a single room) and apartment" in r.text


@pytest.mark.parametrize("solver", ["greedy", "lookahead", "plan2place_all_objects"])
def test_place_keeps_the_given_poses_and_names_a_stranger(db_url, solver):
    """POST /place: the plan's layout with the kept poses as they are; a kept id not in the plan is a 422."""
    api = client(db_url)
    gen = api.post("/generate", json={"instruction": "Put a chilled bread on the counter", "room_type": "kitchen",
                                      "solver": "greedy"}).json()
    first = gen["layout"]["placements"][0]
    pose = [round(first["x"] + 0.05, 4), first["z"], first["rotation"]]
    placed = api.post("/place", json={"plan": gen["plan"], "solver": solver, "keep": {first["id"]: pose}})
    assert placed.status_code == 200
    layout = placed.json()
    kept = next(p for p in layout["placements"] if p["id"] == first["id"])
    assert [kept["x"], kept["z"], kept["rotation"]] == pose and layout["solver"] == solver
    assert len(layout["placements"]) == len(gen["layout"]["placements"])
    bad = api.post("/place", json={"plan": gen["plan"], "keep": {"sofa-9": [1, 1, 0]}})
    assert bad.status_code == 422 and "not objects of plan scene-0: sofa-9" in bad.text
    away = api.post("/place", json={"plan": gen["plan"], "keep": {first["id"]: [-1.5, 1, 0]}})  # x and z swapped, say
    room = gen["plan"]["room"]
    assert away.status_code == 422 and \
        f"outside the {room['width']} x {room['depth']} m room of plan scene-0: {first['id']} at (-1.5, 1.0)" in away.text
    assert api.post("/place", json={"plan": gen["plan"], "solver": "best"}).status_code == 422


def test_generate_infers_the_room_type_when_asked(db_url):
    api = client(db_url)
    gen = api.post("/generate", json={"instruction": "Look at the book under the lamp", "room_type": "infer"})
    assert gen.status_code == 200 and gen.json()["task_graph"]["room_type"] == "bedroom"


def test_the_solvers_and_room_types_a_request_may_name(db_url):
    """GET /solvers and GET /room-types: what `solver` and `room_type` take, so a script need not guess; each
    listed value is accepted by POST /generate."""
    from models.placement import DEFAULT_SOLVER, SOLVERS
    api = client(db_url)
    solvers = api.get("/solvers").json()
    assert solvers["default"] == DEFAULT_SOLVER and sorted(solvers["solvers"]) == sorted(SOLVERS)
    assert all(line for line in solvers["solvers"].values())
    kinds = api.get("/room-types").json()
    assert "kitchen" in kinds["room_types"] and (kinds["infer"], kinds["apartment"]) == ("infer", "apartment")
    for room_type in (kinds["room_types"][-1], kinds["infer"]):
        r = api.post("/generate", json={"instruction": "Put a mug in the sink", "room_type": room_type,
                                        "solver": "dfs"})
        assert r.status_code == 200, r.text
