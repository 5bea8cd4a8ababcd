"""Haptic profiles from AI2-THOR properties; the README table is the generated one."""

from __future__ import annotations

import json
from pathlib import Path

from interaction_scenes import COOL, kitchen

from models.exports.procthor_house import to_house
from models.interaction import haptic_class, haptic_profiles, profile_for, readme_table, state_class
from models.interaction.haptics import BLACK, COLOURS
from models.values.interaction import GLOVE_MOTORS


def test_classes_follow_the_properties():
    assert haptic_class("Microwave")[0] == "hot"
    assert haptic_class("Toaster")[0] == "hot"
    assert haptic_class("Fridge")[0] == "cold"
    assert haptic_class("FloorLamp")[0] == "light"
    assert haptic_class("Apple")[0] == "normal"
    assert haptic_class("NoSuchThing")[0] == "normal"


def test_colours_are_the_papers_transitions():
    for cls, end in (("cold", (0.0, 0.35, 1.0)), ("light", (1.0, 1.0, 1.0))):
        p = profile_for("x", "x", {"cold": "Fridge", "light": "FloorLamp"}[cls])
        assert p.colour.start == BLACK and p.colour.end == end and p.colour.duration_ms > 0
    hot = profile_for("x", "x", "Microwave").colour
    assert hot.end[0] > hot.end[2]  # warm: red over blue
    assert len({c[0] for c in COLOURS.values()}) == 4


def test_motor_intensities_are_six_within_range_and_grow_with_mass():
    egg, pot = profile_for("e", "e", "Egg"), profile_for("p", "p", "Pot")
    for p in (egg, pot, profile_for("f", "f", "Fridge")):
        for pattern in (p.touch, p.grasp):
            assert len(pattern.intensities) == len(GLOVE_MOTORS) == 6
            assert all(0 <= v <= 100 for v in pattern.intensities)
            assert pattern.duration_ms > 0
    assert sum(pot.grasp.intensities) > sum(egg.grasp.intensities)
    assert pot.grasp.intensities[5] > egg.grasp.intensities[5]  # the wrist carries the weight
    sofa = profile_for("s", "s", "Sofa")
    assert sofa.grasp.intensities[5] == 0  # not pickupable: fingertips only


def test_cooled_and_heated_state_change_the_class():
    assert state_class(cooled=True, heated=False) == "cold"
    assert state_class(cooled=False, heated=True) == "hot"
    assert state_class(cooled=False, heated=False) is None
    bread = profile_for("b", "b", "Bread", "cold")
    assert bread.haptic_class == "cold" and bread.colour.end == COLOURS["cold"][0]
    assert "fridge" in bread.why


def test_profiles_cover_every_object_with_house_ids_and_serialise():
    scene = kitchen(COOL)
    house = to_house(scene)
    profiles = haptic_profiles(scene)
    ids = {o["id"] for o in house["objects"]} | {c["id"] for o in house["objects"] for c in o["children"]}
    assert {p.object_id for p in profiles} == ids
    assert {p.scene_object_id for p in profiles} == {o.id for o in scene.all_objects()}
    json.loads(json.dumps([p.model_dump(mode="json") for p in profiles]))
    by_type = {p.object_type: p.haptic_class for p in profiles}
    assert by_type["Fridge"] == "cold" and by_type["Microwave"] == "hot" and by_type["FloorLamp"] == "light"


def test_readme_table_is_the_generated_one():
    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    assert readme_table() in readme
