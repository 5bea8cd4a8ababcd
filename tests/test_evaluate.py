"""Every constraint of constraints.md on hand-built poses whose answer is known."""

import numpy as np
import pytest

from models.constraints.evaluate import AROUND_MAX_GAP, FLOAT_TOL, NEAR_MAX, Poses, placement, relation, relation_met
from models.constraints.language import RELATIONS

# B: a 2 m wide, 1 m deep table at (5, 5) facing +z (north).
B = Poses.one(5, 5, 0, 2.0, 1.0)


def rel(name, x, z, rotation=0.0, w=0.5, d=0.5):
    energy, ok = relation(name, Poses.one(x, z, rotation, w, d), B)
    return bool(ok[0]), float(energy[0])


@pytest.mark.parametrize("name,pose,expected", [
    ("near", (5, 6.4), True),        # gap 0.65
    ("near", (5, 7.0), False),       # gap 1.25
    ("far", (5, 7.5), True),         # gap 1.75
    ("far", (5, 6.5), False),
    ("in front of", (5, 6.2), True),
    ("in front of", (5, 3.8), False),  # behind it
    ("in front of", (7, 6.2), False),  # ahead, but beside the front axis
    ("behind", (5, 3.8), True),
    ("side of", (6.5, 5), True),
    ("side of", (5, 6.2), False),
    ("right of", (6.5, 5), True),    # right of B is +x when B faces +z
    ("left of", (6.5, 5), False),
    ("left of", (3.5, 5), True),
    ("center aligned", (5.05, 7), True),
    ("center aligned", (5.3, 7), False),
])
def test_relation_satisfaction(name, pose, expected):
    assert rel(name, *pose)[0] is expected


def test_face_to_and_around_depend_on_orientation():
    assert rel("face to", 5, 7, rotation=180)[0] and not rel("face to", 5, 7, rotation=0)[0]
    assert rel("around", 5, 6.0, rotation=180)[0]      # touching B's front, facing it
    assert not rel("around", 5, 6.0, rotation=90)[0]   # close, but facing away
    assert rel("face same as", 9, 9, rotation=30)[0] and not rel("face same as", 9, 9, rotation=90)[0]


def test_energies_are_zero_when_met_and_grow_with_the_violation():
    assert rel("near", 5, 6.0)[1] == 0
    e1, e2 = rel("near", 5, 7.0)[1], rel("near", 5, 8.0)[1]
    assert 0 < e1 < e2
    assert rel("far", 5, 9)[1] == 0 < rel("far", 5, 6)[1]


@pytest.mark.parametrize("x,z,rotation,expected", [
    (2.0, 0.25, 0, True),     # back on the south wall, facing north
    (2.0, 0.25, 180, False),  # touching the wall but facing it
    (0.25, 2.0, 90, True),    # back on the west wall, facing east
    (3.75, 2.0, 270, True),   # back on the east wall
    (2.0, 2.0, 0, False),
])
def test_edge(x, z, rotation, expected):
    _, ok = placement("edge", Poses.one(x, z, rotation, 1.0, 0.5), 4.0, 4.0)
    assert bool(ok[0]) is expected


def test_middle():
    assert placement("middle", Poses.one(2, 2, 0, 1, 1), 4, 4)[1][0]
    assert not placement("middle", Poses.one(0.8, 2, 0, 1, 1), 4, 4)[1][0]  # 0.3 m from the west wall


@pytest.mark.parametrize("name,pose", [
    ("near", (5, 6.4)), ("near", (5, 6.45)),  # gaps 0.65 and 0.7: met, so no energy
    ("in front of", (5, 6.2)), ("in front of", (5, 6.9)),  # met at gaps 0.45 and 1.15
    ("behind", (5, 3.8)), ("side of", (6.5, 5)), ("side of", (6.8, 5)),
    ("right of", (6.5, 5)), ("left of", (3.5, 5)), ("center aligned", (5.05, 7)),
])
def test_a_met_constraint_has_zero_energy(name, pose):
    ok, energy = rel(name, *pose)
    assert ok and energy == 0


def test_a_gap_off_a_threshold_in_the_last_bits_meets_it_and_a_real_miss_does_not():
    """The judge measures gaps between polygons (rotated by sin and cos), the placers between boxes: a chair at
    the 0.6 m of `around` came out 0.6000000000000002 in the judge and 0.6 in the polish, which counted it met
    and the metric not (seen-00022)."""
    chair = Poses.one(5, 6.6 + 0.25, 180, 0.5, 0.5)  # facing the table, 0.6 m beyond its front
    for gap, met in [(AROUND_MAX_GAP, True), (np.nextafter(AROUND_MAX_GAP, 1), True),
                     (AROUND_MAX_GAP + 100 * FLOAT_TOL, False)]:
        assert bool(relation("around", chair, B, gap=np.array([gap]))[1][0]) == met, gap
    assert bool(relation("near", chair, B, gap=np.array([NEAR_MAX + 2e-16]))[1][0])
    assert not relation("near", chair, B, gap=np.array([NEAR_MAX + 1e-6]))[1][0]


@pytest.mark.parametrize("name", RELATIONS)
def test_relation_met_is_relations_satisfied_mask_for_every_pose_and_both_directions(name):
    rng = np.random.default_rng(0)
    n = 2000  # random poses around B on a 0.1 m grid, some of them on a threshold
    xz = np.round(rng.uniform(2, 8, (2, n)), 1)
    many = Poses(xz[0], xz[1], rng.choice([0.0, 90.0, 180.0, 270.0], n), 0.6, 0.4)
    assert 0 < relation(name, many, B)[1].sum() < n  # both answers occur
    assert np.array_equal(relation_met(name, many, B), relation(name, many, B)[1])
    assert np.array_equal(relation_met(name, B, many), relation(name, B, many)[1])
