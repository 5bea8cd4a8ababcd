"""Each energy term on layouts whose answer is known, and the exact and vectorised energies agreeing."""

import math

import numpy as np
import pytest

from models.energy.exact import layout_energy
from models.energy.prior import build, relation_prior
from models.energy.vectorised import CandidateEnergy
from models.placement.candidates import CandidateScorer
from models.placement.problem import PlacementProblem
from models.values import ConstraintPlan, Placement, Size

ROOM = {"type": "kitchen", "width": 4.0, "depth": 4.0, "doors": [{"wall": "south", "center": 2.0, "width": 1.0}]}


def make(objects, constraints=""):
    plan = ConstraintPlan.model_validate({"id": "e", "room": ROOM, "constraints": constraints, "objects": [
        {"id": oid, "type": t, "size": {"x": w, "y": 1, "z": d}, "role": role} for oid, t, w, d, role, *_ in objects]})
    placements = [Placement(id=oid, type=t, x=pose[0], z=pose[1], rotation=pose[2], size=Size(x=w, y=1, z=d))
                  for oid, t, w, d, role, pose in objects]
    return plan, placements


def test_collision_is_log_of_squared_overlap():
    plan, pl = make([("a", "Box", 1, 1, "context", (1.5, 2, 0)), ("b", "Box", 1, 1, "context", (2.0, 2, 0))])
    assert layout_energy(plan, pl).collision == pytest.approx(math.log1p(0.5 ** 2))


def test_out_of_bounds_counts_the_share_outside():
    plan, pl = make([("a", "Box", 1, 1, "context", (0.0, 2, 0))])  # half of it west of the wall
    assert layout_energy(plan, pl).oob == pytest.approx(math.log1p(0.5 ** 2))


def test_affordance_clearance_outside_the_room_or_blocked():
    facing_wall = make([("f", "Fridge", 0.8, 0.7, "context", (2, 3.65, 0))])  # at the north wall, facing it
    assert layout_energy(*facing_wall).aff == pytest.approx(1.0)
    blocked = make([("f", "Fridge", 0.8, 0.7, "context", (2, 3.65, 180)), ("b", "Box", 0.5, 0.5, "context", (2, 3.0, 0))])
    assert layout_energy(*blocked).aff == pytest.approx(1.0)
    free = make([("f", "Fridge", 0.8, 0.7, "context", (2, 3.65, 180))])
    assert layout_energy(*free).aff == 0


def test_navigation_reachability():
    open_room = make([("t", "Dresser", 1, 0.5, "anchor", (2, 3.75, 180))])
    assert layout_energy(*open_room).nav == 0
    # a wall of furniture across the room cuts the anchor off from the door
    walled = make([("t", "Dresser", 1, 0.5, "anchor", (2, 3.75, 180)),
                   ("w", "Dresser", 4.0, 0.5, "context", (2, 2.0, 0))])
    assert layout_energy(*walled).nav == 1.0


def test_relational_energy_is_zero_when_met_and_grows_with_violation():
    def rel(x):
        plan, pl = make([("a", "Chair", 0.5, 0.5, "context", (x, 2, 0)), ("b", "Box", 0.5, 0.5, "context", (1, 2, 0))],
                        "a | middle | near, b\nb | middle")
        return layout_energy(plan, pl).rel
    assert rel(1.6) == pytest.approx(0, abs=1e-9)
    assert rel(2.5) == pytest.approx(0, abs=1e-9)  # gap 1.0: still near, so no energy
    assert 0 < rel(2.8) < rel(3.2)


def test_the_prior_file_is_what_the_bundled_ithor_data_gives():
    from importlib import resources
    assert resources.files("models").joinpath("data/relation_prior.json").read_text() == build()


def test_prior_prefers_what_ithor_rooms_show():
    prior = relation_prior()
    assert prior.wall_energy("bedroom", "Bed", True) < prior.wall_energy("bedroom", "Bed", False)
    e = prior.pair_energy("living room", "ArmChair", "Sofa", np.array([0.5, 4.5]), np.array([90, 90]))
    assert e[0] < e[1]


def random_case(pipeline, seed):
    gen = pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=seed)
    problem = PlacementProblem.from_plan(gen.plan)
    placed = gen.layout.placements[:-1]
    obj = gen.plan.object(gen.layout.placements[-1].id)
    return gen.plan, problem, placed, obj


class _P:
    def __init__(self, p):
        self.id, self.x, self.z, self.rotation, self.width, self.depth = p.id, p.x, p.z, p.rotation, p.size.x, p.size.z


@pytest.mark.parametrize("seed", range(6))
def test_vectorised_energy_agrees_with_exact(pipeline, seed):
    """Tolerance 1e-6 on every term and the total with exact navigation; the fast navigation mode is
    an approximation (it misses cuts of the free space away from the covered strips) and is only
    required to agree on half of the candidates here (the benchmark prints its agreement rate)."""
    plan, problem, placed, obj = random_case(pipeline, seed)
    cands = CandidateScorer(problem).candidates(obj)
    idx = np.random.default_rng(seed).choice(len(cands), size=30, replace=False)
    energy = CandidateEnergy(problem, [_P(p) for p in placed])
    exact_nav, fast = energy.score(obj, cands[idx], nav_mode="exact"), energy.score(obj, cands[idx])
    fast_agree = 0
    for k, i in enumerate(idx):
        x, z, r = cands[i]
        exact = layout_energy(plan, placed + [Placement(id=obj.id, type=obj.type, x=x, z=z, rotation=r, size=obj.size)],
                              problem).as_dict()
        for term in exact:
            assert exact_nav[term][k] == pytest.approx(exact[term], abs=1e-6), term
        for term in ("rel", "collision", "oob", "aff"):
            assert fast[term][k] == pytest.approx(exact[term], abs=1e-6), term
        fast_agree += abs(fast["nav"][k] - exact["nav"]) < 1e-9
    assert fast_agree >= 0.5 * len(idx)


def _ordered_case():
    """A kitchen plan of three objects (one anchor) and a complete layout that meets every constraint."""
    return make([("f", "Fridge", 0.8, 0.7, "anchor", (0.6, 3.65, 180)),
                 ("c", "Chair", 0.5, 0.5, "context", (2.5, 2.0, 0)),
                 ("t", "Box", 0.5, 0.5, "context", (3.2, 2.0, 0))],
                "f | edge\nc | middle | near, t\nt | middle")


def test_empty_is_worst_then_missing_one_then_complete():
    plan, pl = _ordered_case()
    complete = layout_energy(plan, pl)
    assert complete.total == pytest.approx(0, abs=1e-9)
    missing_context = layout_energy(plan, pl[:1] + pl[2:])
    missing_anchor = layout_energy(plan, pl[1:])
    empty = layout_energy(plan, [])
    assert missing_context.missing == pytest.approx(1 / 3) and empty.missing == 1.0
    assert missing_anchor.nav == 1.0 and empty.nav == 1.0  # an unplaced task object is unreachable
    assert empty.total > missing_anchor.total > missing_context.total > complete.total


def test_pending_objects_are_not_charged_until_the_episode_ends():
    plan, pl = _ordered_case()
    partial = layout_energy(plan, pl[:1], pending={"c", "t"})
    assert partial.missing == 0 and partial.total == pytest.approx(0, abs=1e-9)
    assert layout_energy(plan, pl[:1]).missing == pytest.approx(2 / 3)
    # a pending task object is not yet a navigation target; once the episode ends it is
    assert layout_energy(plan, pl[1:], pending={"f"}).nav == 0
    assert layout_energy(plan, pl[1:]).nav == 1.0


def test_vectorised_charges_missing_and_pending_like_exact():
    plan, pl = _ordered_case()
    problem = PlacementProblem.from_plan(plan)
    obj = plan.object("c")
    cand = np.array([[2.5, 2.0, 0.0]])
    for pending in ((), ("t",)):
        exact = layout_energy(plan, pl[:2], problem, pending=pending).as_dict()
        vec = CandidateEnergy(problem, [_P(pl[0])], pending=pending).score(obj, cand, nav_mode="exact")
        for term in exact:
            assert vec[term][0] == pytest.approx(exact[term], abs=1e-6), (pending, term)


@pytest.mark.parametrize("seed", range(3))
def test_the_terms_of_a_set_up_alone_are_the_exact_energy_of_its_objects(pipeline, seed):
    """`CandidateEnergy.terms()`, the layout without a candidate (the polish's baseline), labels the free space
    exactly: equal to `layout_energy` of the placed objects, whether the others are pending or left out."""
    plan, problem, placed, obj = random_case(pipeline, seed)
    rest = {o.id for o in plan.objects} - {p.id for p in placed}
    for pending in (set(), rest, {obj.id}):
        exact = layout_energy(plan, placed, problem, pending=pending).as_dict()
        terms = CandidateEnergy(problem, [_P(p) for p in placed], pending=pending).terms()
        assert (exact["missing"] > 0) == (not pending)  # `obj` is charged as left out unless pending
        for term in exact:
            assert terms[term] == pytest.approx(exact[term], abs=1e-9), (pending, term)


def test_the_flood_fill_reaches_what_labelling_the_free_space_reaches():
    """`navigation.reachable_from` (a compiled flood fill) against the components scipy labels, on random grids
    from nearly free to nearly blocked, including start cells that are blocked."""
    from scipy import ndimage

    from models.energy.navigation import reachable_from
    rng = np.random.default_rng(0)
    for _ in range(500):
        nx, nz = rng.integers(1, 60, 2)
        blocked = rng.random((nx, nz)) < rng.random()
        start = np.zeros((nx, nz), bool)
        start[rng.integers(0, nx, 3), rng.integers(0, nz, 3)] = True
        labels, _ = ndimage.label(~blocked)
        ids = np.unique(labels[start & ~blocked])
        assert np.array_equal(reachable_from(blocked, start), np.isin(labels, ids[ids > 0]))
