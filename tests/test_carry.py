"""Carrying an object from one room of an apartment to another (models.scene.carry): what stands on it goes along,
the ids keep saying which room holds them, both rooms' constraint texts follow, and the robot's visits, the task
objects' rooms and the house follow."""

import pytest

from models.constraints.holodeck_text import without_object
from models.scene.apartment import house_objects
from models.scene.carry import carry, room_holding

BREAD = "Put a chilled bread on the counter"
ROOMS = ["kitchen", "living room", "bedroom"]
SEED = 3


@pytest.fixture(scope="module")
def flat(pipeline):
    return pipeline.generate_apartment(BREAD, ROOMS, seed=SEED)


def holder(flat):
    """The kitchen's object that holds the bread (the robot fetches the bread from it)."""
    return next(o for o in flat.plans[0].objects if o.holds)


def test_the_bread_s_table_goes_to_the_living_room_with_the_bread(flat):
    table = holder(flat)
    moved, new_id = carry(flat, table.id, 1, 1.5, 2.0, 90, SEED)
    assert new_id == "r2-" + table.id.split("-", 1)[1]
    assert table.id not in {o.id for o in moved.plans[0].objects} and table.id not in moved.plans[0].constraints
    assert moved.plans[1].constraints.splitlines()[-1] == f"{new_id} | edge"
    arrived = moved.plans[1].object(new_id)
    assert arrived.holds == ["key"] and arrived.size == table.size
    bread = next(s for s in moved.plan.room_plans[1].surface_objects if s.type == "Bread")
    assert bread.parent == new_id and bread.id.startswith("r2-")
    assert not any(s.type == "Bread" for s in moved.plan.room_plans[0].surface_objects)
    assert moved.plan.assignment["Bread"] == "room|2" and moved.plan.assignment["Fridge"] == "room|1"
    assert new_id in moved.path.visits and table.id not in moved.path.visits + moved.path.unreachable
    hr = moved.floorplan.rooms[1]
    shown = next(o for o in house_objects(moved) if o.id == new_id)
    assert (shown.x, shown.z, shown.rotation) == pytest.approx((hr.x + 1.5, hr.z + 2.0, 90))
    assert [c.type for c in shown.children] == ["Bread"]
    assert moved.layouts[2] == flat.layouts[2]  # the room not involved as it was


def test_a_carried_object_keeps_its_number_unless_taken_then_the_next_free_one(flat):
    can = next(o.id for o in flat.plans[0].objects if o.type == "GarbageCan")
    living_cans = [o.id for o in flat.plans[1].objects if o.type == "GarbageCan"]
    assert living_cans == ["r2-garbagecan-0"]  # the living room has one already
    there, new_id = carry(flat, can, 1, 1.0, 1.0, 0, SEED)
    assert new_id == "r2-garbagecan-1"
    back, again = carry(there, new_id, 0, 0.5, 0.5, 0, SEED)
    assert again == "r1-garbagecan-1" and room_holding(back, again) == 0  # free in the kitchen: its number kept
    assert [o.id for o in back.plans[1].objects if o.type == "GarbageCan"] == living_cans


def test_constraints_that_target_the_carried_object_are_dropped_and_the_rest_kept_as_written():
    text = "a-0 | edge | near, b-0\nb-0 | middle\nc-0 |  edge | near, b-0 | face to, a-0\n# note"
    assert without_object(text, "b-0") == "a-0 | edge\nc-0 | edge | face to, a-0\n# note"
    assert without_object(text, "z-9") == text


@pytest.mark.parametrize("to,words", [(0, "not 1"), (7, "not 8")])
def test_a_carry_to_the_same_or_a_missing_room_is_refused(flat, to, words):
    with pytest.raises(ValueError, match=words):
        carry(flat, holder(flat).id, to, 1.0, 1.0, 0, SEED)


def test_an_unknown_object_is_refused_by_name(flat):
    with pytest.raises(ValueError, match="r9-ghost-0 is not a floor object"):
        carry(flat, "r9-ghost-0", 1, 1.0, 1.0, 0, SEED)
