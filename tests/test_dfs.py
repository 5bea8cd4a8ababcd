import itertools

import pytest

from models.geometry import Footprint, inside_room, overlap_area
from models.placement import UnknownSolver, get_solver
from models.values import ConstraintPlan

ROOM = {"type": "kitchen", "width": 4.2, "depth": 5.0, "doors": [{"wall": "south", "center": 1.1, "width": 0.9}],
        "windows": [{"wall": "north", "center": 2.0, "width": 1.2}]}


def obj(i, type_="Chair", x=0.5, z=0.5, role="context"):
    return {"id": f"{type_.lower()}-{i}", "type": type_, "size": {"x": x, "y": 1.0, "z": z}, "role": role}


def plan(objects, constraints="", room=ROOM):
    return ConstraintPlan.model_validate({"id": "t", "room": room, "objects": objects, "constraints": constraints})


def footprints(layout):
    return {p.id: Footprint(p.x, p.z, p.size.x, p.size.z, p.rotation) for p in layout.placements}


def check_valid(p, layout):
    fps = footprints(layout)
    assert {o.id for o in p.objects} == set(fps) | {u.id for u in layout.unplaced}
    assert not set(fps) & {u.id for u in layout.unplaced}
    for f in fps.values():
        assert inside_room(f, p.room.width, p.room.depth, tol=1e-6)
    for a, b in itertools.combinations(fps.values(), 2):
        assert overlap_area(a, b) < 1e-4


def test_places_the_interfaces_example_and_meets_its_constraints():
    p = plan([obj(0, "Fridge", 0.75, 0.7, "inference"), obj(0, "CounterTop", 2.4, 0.65, "anchor")],
             "fridge-0 | edge | near, countertop-0\ncountertop-0 | edge")
    layout = get_solver("dfs").solve(p, seed=0)
    check_valid(p, layout)
    assert not layout.unplaced and layout.solver == "dfs"
    fps = footprints(layout)
    from models.geometry import gap
    assert gap(fps["fridge-0"], fps["countertop-0"]) <= 1.0


def test_same_seed_same_layout_and_seeds_differ():
    p = plan([obj(i) for i in range(5)])
    solver = get_solver("dfs")
    a, b, c = solver.solve(p, seed=1), solver.solve(p, seed=1), solver.solve(p, seed=2)
    assert a.placements == b.placements
    assert a.placements != c.placements


def test_objects_too_large_or_without_room_are_listed_not_dropped():
    big = obj(0, "Bed", 6.0, 6.0)
    crowd = [obj(i, "Dresser", 1.9, 1.9) for i in range(8)]
    p = plan([big] + crowd)
    layout = get_solver("dfs").solve(p, seed=0, time_budget_s=1.0)
    check_valid(p, layout)
    reasons = {u.id: u.reason for u in layout.unplaced}
    assert "larger than the room" in reasons["bed-0"]
    assert len(reasons) >= 4 and all(reasons.values())


def test_door_clearance_is_kept_free():
    p = plan([obj(i, "Dresser", 1.0, 0.5) for i in range(6)])
    layout = get_solver("dfs").solve(p, seed=0)
    door_zone = Footprint(1.1, 0.45, 1.0, 0.9)
    for f in footprints(layout).values():
        assert overlap_area(f, door_zone) < 1e-4


def test_bad_constraint_text_is_reported_not_fatal():
    p = plan([obj(0), obj(1)], "chair-0 | middle | nxt to, chair-1 | near, ghost-3\nchair-1 | sideways")
    layout = get_solver("dfs").solve(p, seed=0)
    assert len(layout.placements) == 2 and len(layout.warnings) == 3


def test_unknown_solver_names_the_choices():
    with pytest.raises(UnknownSolver, match="available: dfs"):
        get_solver("simulated-annealing")
