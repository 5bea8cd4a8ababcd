"""Each placement metric on hand-built layouts whose answer is known."""

import pytest

from models.metrics import scene_metrics
from models.values import ConstraintPlan, Layout, Placement, Size, Timing, Unplaced

ROOM = {"type": "bedroom", "width": 4.0, "depth": 4.0, "doors": [{"wall": "south", "center": 2.0, "width": 1.0}]}


def case(objects, unplaced=(), constraints="", total_s=0.4):
    plan = ConstraintPlan.model_validate({"id": "m", "room": ROOM, "constraints": constraints, "objects": [
        {"id": o[0], "type": o[1], "size": {"x": o[2], "y": 1, "z": o[3]}, "role": o[4]} for o in objects]})
    placements = [Placement(id=o[0], type=o[1], x=o[5][0], z=o[5][1], rotation=o[5][2], size=Size(x=o[2], y=1, z=o[3]))
                  for o in objects if o[0] not in unplaced]
    layout = Layout(plan_id="m", solver="test", seed=0, placements=placements,
                    unplaced=[Unplaced(id=u, reason="test") for u in unplaced],
                    timing=Timing(total_s=total_s, per_object_s=total_s / len(objects)))
    return scene_metrics(plan, layout)


BED = ("bed", "Bed", 1.4, 2.0, "anchor", (2.0, 2.95, 180))
LAMP = ("lamp", "FloorLamp", 0.4, 0.4, "inference", (0.3, 3.7, 180))
BOX = ("box", "Box", 0.5, 0.5, "context", (3.5, 0.5, 0))


def test_a_clean_layout():
    m = case([BED, LAMP, BOX])
    assert (m.cnt, m.sr, m.oob, m.collisions) == (1.0, 1.0, 0.0, 0)
    assert m.key_nav == 1.0 and m.nav == pytest.approx(1.0)
    assert m.pto == pytest.approx(0.4 / 3)


def test_count_and_success_with_an_unplaced_task_object():
    m = case([BED, LAMP, BOX], unplaced=("lamp",))
    assert m.cnt == pytest.approx(2 / 3) and m.sr == 0.0
    m = case([BED, LAMP, BOX], unplaced=("box",))
    assert m.sr == 1.0


def test_out_of_bounds_and_collisions():
    outside = ("out", "Box", 1, 1, "context", (4.0, 2.0, 0))
    overlapping = ("ov", "Box", 0.5, 0.5, "context", (3.4, 0.6, 0))
    m = case([BED, BOX, outside, overlapping])
    assert m.oob == pytest.approx(1 / 4) and m.collisions == 1


def test_navigability_when_a_dresser_row_splits_the_room():
    splitter = ("row", "Dresser", 4.0, 0.6, "context", (2.0, 2.0, 0))
    behind = ("desk", "Desk", 1.0, 0.6, "anchor", (2.0, 3.7, 180))
    m = case([splitter, behind])
    assert m.key_nav == 0.0
    assert 0.3 < m.nav < 0.7  # two similar halves: the larger is about half the free space


def test_constraint_satisfaction():
    chair = ("chair", "Chair", 0.5, 0.5, "context", (2.0, 1.6, 0))
    table = ("table", "DiningTable", 1.0, 1.0, "context", (2.0, 2.5, 0))
    ok = case([chair, table], constraints="chair | middle | near, table | face to, table\ntable | middle")
    assert ok.constraint_satisfaction == 1.0
    bad = case([chair, table], constraints="chair | middle | far, table | face to, table\ntable | edge")
    assert bad.constraint_satisfaction == pytest.approx(2 / 4)
    missing = case([chair, table], unplaced=("table",), constraints="chair | middle | near, table\ntable | middle")
    assert missing.constraint_satisfaction == pytest.approx(1 / 3)


def test_an_empty_layout_earns_nothing():
    m = case([BED, LAMP, BOX], unplaced=("bed", "lamp", "box"))
    assert (m.cnt, m.sr, m.key_nav, m.nav, m.oob, m.constraint_satisfaction) == (0.0, 0.0, 0.0, 0.0, 1.0, 0.0)
    assert not m.complete


def test_dropping_an_object_never_raises_nav_or_lowers_oob():
    full = case([BED, LAMP, BOX])
    dropped = case([BED, LAMP, BOX], unplaced=("box",))
    assert dropped.nav == 0.0 < full.nav
    assert dropped.oob == pytest.approx(1 / 3) and full.oob == 0


def test_a_plan_without_task_objects_is_not_applicable():
    m = case([("box", "Box", 0.5, 0.5, "context", (3.5, 0.5, 0))])
    assert m.sr is None and m.key_nav is None and m.n_task == 0


def test_the_start_receptacle_of_the_picked_object_is_a_task_object():
    """A dining table holding the key object (the bread to pick up) must be placed and reachable."""
    table = {"id": "table", "type": "DiningTable", "size": {"x": 1, "y": 1, "z": 1}, "role": "context", "holds": ["key"]}
    plan = ConstraintPlan.model_validate({"id": "m", "room": ROOM, "objects": [table]})
    walled = ConstraintPlan.model_validate({"id": "m", "room": ROOM, "objects": [
        table, {"id": "row", "type": "Dresser", "size": {"x": 4.0, "y": 1, "z": 0.6}, "role": "context"}]})
    at = Placement(id="table", type="DiningTable", x=2, z=3.2, rotation=180, size=Size(x=1, y=1, z=1))
    row = Placement(id="row", type="Dresser", x=2, z=2.0, rotation=0, size=Size(x=4.0, y=1, z=0.6))
    t = Timing(total_s=0.1, per_object_s=0.1)
    placed = scene_metrics(plan, Layout(plan_id="m", solver="t", seed=0, placements=[at], timing=t))
    assert placed.n_task == 1 and placed.sr == 1.0 and placed.key_nav == 1.0
    missing = scene_metrics(plan, Layout(plan_id="m", solver="t", seed=0, placements=[], timing=t))
    assert missing.sr == 0.0 and missing.key_nav == 0.0
    cut_off = scene_metrics(walled, Layout(plan_id="m", solver="t", seed=0, placements=[at, row], timing=t))
    assert cut_off.sr == 1.0 and cut_off.key_nav == 0.0


def test_nav_counts_only_the_free_space_reachable_from_the_door():
    """A row of dressers just north of the door: the largest free region is the far side (about 3/4 of
    the free space), but the robot can use only the strip by the door."""
    row = ("row", "Dresser", 4.0, 0.4, "context", (2.0, 1.0, 0))
    m = case([row])
    assert m.nav < 0.3
