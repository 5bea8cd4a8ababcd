"""The house JSON has the structure of a real ProcTHOR house; the GLB opens and holds every object."""

import io
import json
from pathlib import Path

import pytest
import trimesh

from models.exports.glb import to_glb
from models.exports.procthor_house import to_house
from models.world import catalogue

EXAMPLE = json.loads((Path(__file__).parent / "fixtures" / "procthor_house_example.json").read_text())


@pytest.fixture(scope="module")
def scene(pipeline):
    return pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=1).scene


def type_shape(value):
    """JSON value kinds, with ints and floats both 'number' (ProcTHOR writes 0 and 0.0 alike)."""
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, (int, float)):
        return "number"
    return type(value).__name__


def check_like(ours: dict, theirs: list[dict], where: str):
    """Every key we write exists in the example with the same kind of value, and the example's common keys are all there."""
    kinds: dict[str, set] = {}
    for item in theirs:
        for k, v in item.items():
            kinds.setdefault(k, set()).add(type_shape(v))
    common = set.intersection(*(set(i) for i in theirs))
    assert common <= set(ours), f"{where}: missing {common - set(ours)}"
    for k, v in ours.items():
        assert k in kinds, f"{where}: unknown key {k}"
        assert type_shape(v) in kinds[k], f"{where}.{k}: {type_shape(v)} not in {kinds[k]}"


def test_house_matches_the_procthor_example(scene):
    house = to_house(scene)
    assert set(house) == set(EXAMPLE)
    for key in ("rooms", "walls", "doors", "windows", "objects"):
        for item in house[key]:
            check_like(item, EXAMPLE[key], key)
    for child in (c for o in house["objects"] for c in o["children"]):
        check_like(child, [c for o in EXAMPLE["objects"] for c in o.get("children", [])], "children")
    check_like(house["metadata"], [EXAMPLE["metadata"]], "metadata")
    check_like(house["metadata"]["agent"], [EXAMPLE["metadata"]["agent"]], "agent")
    check_like(house["proceduralParameters"], [EXAMPLE["proceduralParameters"]], "proceduralParameters")
    assert house["metadata"]["schema"] == "1.0.0"


def test_house_references_are_consistent(scene):
    house = to_house(scene)
    wall_ids = {w["id"] for w in house["walls"]}
    for hole in house["doors"] + house["windows"]:
        assert hole["wall0"] in wall_ids and hole["wall1"] in wall_ids
        assert hole["room0"] == house["rooms"][0]["id"]
    ids = [o["id"] for o in house["objects"]] + [c["id"] for o in house["objects"] for c in o["children"]]
    assert len(ids) == len(set(ids))


def test_every_asset_id_is_real(scene):
    house = to_house(scene)
    assets = {a.asset_id for t in catalogue().types.values() for a in t.assets}
    everything = house["objects"] + [c for o in house["objects"] for c in o["children"]]
    assert all(o["assetId"] in assets for o in everything)
    assert all(h["assetId"] in assets for h in house["doors"] + house["windows"])


def test_glb_opens_with_every_object_named(scene):
    loaded = trimesh.load(io.BytesIO(to_glb(scene)), file_type="glb")
    names = set(loaded.geometry)
    assert {o.id for o in scene.all_objects()} <= names and "floor" in names
    lo, hi = loaded.bounds
    # z is negated for glTF's right-handed axes; the floor spans the room
    assert hi[0] == pytest.approx(scene.room.width + 0.1, abs=0.01)
    assert lo[2] == pytest.approx(-scene.room.depth - 0.1, abs=0.01)
