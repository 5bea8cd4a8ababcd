import math
import os
import subprocess
import sys

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from models.constraints.evaluate import Poses, box_gap
from models.geometry import Footprint, boxes, front, gap, half_extents, inside_room, overlap_area, overlap_many, right

sizes = st.floats(0.05, 3.0)
coords = st.floats(-5, 5)
right_angles = st.sampled_from([0.0, 90.0, 180.0, 270.0])
any_angle = st.floats(0, 360)


def test_rotation_convention_of_interfaces_md():
    assert np.allclose(front(0), (0, 1)) and np.allclose(front(90), (1, 0))
    assert np.allclose(front(180), (0, -1)) and np.allclose(front(270), (-1, 0))
    assert np.allclose(right(0), (1, 0))  # right is (cos r, -sin r)


@given(sizes, sizes, any_angle)
def test_footprint_area_is_width_times_depth(w, d, r):
    assert math.isclose(Footprint(0, 0, w, d, r).polygon().area, w * d, rel_tol=1e-6)


@given(sizes, sizes)
def test_quarter_turn_swaps_extents(w, d):
    ex, ez = half_extents(w, d, 90.0)
    assert math.isclose(ex, d / 2, rel_tol=1e-9, abs_tol=1e-12) and math.isclose(ez, w / 2, rel_tol=1e-9, abs_tol=1e-12)


@given(sizes, sizes, any_angle, st.floats(0.1, 2.0))
def test_front_zone_lies_ahead(w, d, r, depth):
    f = Footprint(1, 2, w, d, r)
    zone = f.front_zone(depth)
    fx, fz = front(r)
    assert math.isclose((zone.x - 1) * fx + (zone.z - 2) * fz, d / 2 + depth / 2, rel_tol=1e-6, abs_tol=1e-9)
    assert overlap_area(f, zone) < 1e-9


@settings(max_examples=200)
@given(coords, coords, sizes, sizes, right_angles, coords, coords, sizes, sizes, right_angles)
def test_vectorised_overlap_and_gap_match_shapely(x1, z1, w1, d1, r1, x2, z2, w2, d2, r2):
    a, b = Footprint(x1, z1, w1, d1, r1), Footprint(x2, z2, w2, d2, r2)
    ba, bb = boxes([x1], [z1], w1, d1, [r1]), boxes([x2], [z2], w2, d2, [r2])
    assert math.isclose(overlap_many(ba, bb)[0, 0], overlap_area(a, b), abs_tol=1e-6)
    pa, pb = Poses.one(x1, z1, r1, w1, d1), Poses.one(x2, z2, r2, w2, d2)
    assert math.isclose(box_gap(pa, pb)[0], gap(a, b), abs_tol=1e-6)


@given(coords, coords, sizes, sizes, any_angle, coords, coords, sizes, sizes, any_angle)
def test_gap_is_zero_exactly_when_footprints_meet(x1, z1, w1, d1, r1, x2, z2, w2, d2, r2):
    a, b = Footprint(x1, z1, w1, d1, r1), Footprint(x2, z2, w2, d2, r2)
    assert (gap(a, b) <= 1e-9) == a.polygon().intersects(b.polygon())
    assert math.isclose(overlap_area(a, b), overlap_area(b, a), abs_tol=1e-9)


def test_inside_room():
    assert inside_room(Footprint(0.5, 0.5, 1, 1), 4, 4)
    assert not inside_room(Footprint(0.4, 0.5, 1, 1), 4, 4)
    assert not inside_room(Footprint(2, 2, 1, 1, 45), 2.5, 2.5)


@settings(max_examples=50)
@given(st.lists(st.tuples(coords, coords, sizes, sizes, right_angles), min_size=1, max_size=30),
       st.lists(st.tuples(coords, coords, sizes, sizes, right_angles), min_size=1, max_size=5))
def test_swept_overlaps_equal_the_dense_ones(many, few):
    from models.geometry import SweptBoxes
    a = np.concatenate([boxes([x], [z], w, d, [r]) for x, z, w, d, r in many])
    b = np.concatenate([boxes([x], [z], w, d, [r]) for x, z, w, d, r in few])
    dense = overlap_many(a, b)
    swept = np.zeros_like(dense)
    for m, (idx, area) in enumerate(SweptBoxes(a).overlaps(b)):
        swept[idx, m] = area
    assert np.allclose(dense, swept, atol=1e-12)


@settings(max_examples=50, deadline=None)  # the first call loads (or compiles) the kernel
@given(st.lists(st.tuples(coords, coords, sizes, sizes, right_angles), min_size=1, max_size=30),
       st.lists(st.tuples(coords, coords, sizes, sizes, right_angles), min_size=0, max_size=5),
       st.sampled_from([0.0, 1e-4, 0.5, math.inf]))
def test_the_compiled_sweep_equals_the_loop_over_overlaps_to_the_bit(many, few, tol):
    """`SweptBoxes.overlapping` (numba) against the numpy loop it replaces in the hard filter and the energy."""
    from models.geometry import SweptBoxes
    a = np.concatenate([boxes([x], [z], w, d, [r]) for x, z, w, d, r in many])
    b = np.concatenate([boxes([x], [z], w, d, [r]) for x, z, w, d, r in few]) if few else np.zeros((0, 4))
    swept, mask, squared = SweptBoxes(a), np.zeros(len(a), bool), np.full(len(a), 0.25)
    for idx, area in swept.overlaps(b):
        mask[idx[area > tol]] = True
        squared[idx] += area ** 2
    compiled = np.full(len(a), 0.25)
    assert np.array_equal(swept.overlapping(b, tol, compiled), mask)
    assert np.array_equal(compiled, squared) and np.array_equal(swept.overlapping(b, tol), mask)


@given(coords, coords, sizes, sizes, sizes, st.sampled_from([0.0, 90.0, 180.0, 270.0, 30.0, 45.0, 359.5]))
def test_one_pose_shortcuts_equal_the_array_functions_to_the_bit(x, z, w, d, clearance, r):
    """`one_box` and `front_boxes` of one pose skip numpy's per-call cost; layouts must not change for it."""
    from models.geometry import one_box
    from models.placement.candidates import front_boxes
    assert np.array_equal(one_box(x, z, w, d, r), boxes(x, z, w, d, r))
    assert np.array_equal(one_box(x, z, w, d, r), boxes(np.array([x]), np.array([z]), w, d, np.array([r]))[0])
    rad = np.radians(np.array([r]))
    off = d / 2 + clearance / 2
    strip = boxes(x + np.sin(rad) * off, z + np.cos(rad) * off, w, clearance, np.array([r]))[0]
    assert np.array_equal(front_boxes(x, z, r, w, d, clearance), strip)


def test_numba_is_imported_only_when_a_placer_first_sweeps():
    code = ("import sys, app.cli, app.api, frontend.server, models.geometry, models.placement.greedy; "
            "assert 'numba' not in sys.modules, 'numba imported at start-up'")
    subprocess.run([sys.executable, "-c", code], check=True, timeout=120)


def test_the_kernels_run_where_numba_can_cache_nothing():
    """A read-only install without a writable home: numba finds no cache directory (forced here by allowing only
    its IPython locator) and the kernels are compiled for the process instead of failing."""
    code = ("import numpy as np; from models.geometry import SweptBoxes; from models.energy.navigation import "
            "reachable_from; a = np.array([[0, 0, 1, 1.0]]); "
            "assert SweptBoxes(a).overlapping(a, 1e-4).tolist() == [True]; "
            "assert reachable_from(np.zeros((2, 2), bool), np.eye(2, dtype=bool)).all()")
    env = {**os.environ, "NUMBA_CACHE_LOCATOR_CLASSES": "IPythonCacheLocator"}
    subprocess.run([sys.executable, "-c", code], check=True, timeout=120, env=env)


def test_the_occupancy_grid_keeps_its_cell_centres_and_marks_what_it_marked_before():
    """The centres are made once per grid (the studio's checks ask about one room on every move); the blocked cells
    are those of centres made afresh."""
    import shapely

    from models.energy import navigation as nav
    grid = nav.Grid(3.1, 2.7)
    polygons = [Footprint(1.0, 1.0, 0.8, 0.5, 90).polygon(), Footprint(2.4, 2.0, 1.2, 0.6, 0).polygon()]
    before = nav._cell_centres.cache_info().hits
    blocked = nav.blocked_by_polygons(grid, polygons)
    assert nav._cell_centres(grid) is nav._cell_centres(nav.Grid(3.1, 2.7))
    assert nav._cell_centres.cache_info().hits >= before + 1
    gx, gz = grid.mesh()
    fresh = shapely.points(gx, gz)
    walls = (gx < nav.ROBOT_RADIUS) | (gz < nav.ROBOT_RADIUS) | (gx > grid.width - nav.ROBOT_RADIUS) | \
        (gz > grid.depth - nav.ROBOT_RADIUS)
    expected = walls | np.any([shapely.dwithin(p, fresh, nav.ROBOT_RADIUS) for p in polygons], axis=0)
    assert blocked.any() and (blocked == expected).all()
