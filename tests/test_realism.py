"""The realism judge: fitted on the held-out iTHOR quarter only, and known answers on hand-built rooms."""

from importlib import resources

from models.energy.prior import judge_scene
from models.metrics.realism import Check, build, checks, realism, realism_checks, stats
from models.values import ConstraintPlan, Layout, Placement, Size, Timing

ROOM = {"type": "bedroom", "width": 4.0, "depth": 4.0, "doors": [{"wall": "south", "center": 2.0, "width": 1.0}]}
OBJECTS = [("bed", "Bed", 1.4, 2.0), ("side", "SideTable", 0.5, 0.5)]


def scored(poses):
    plan = ConstraintPlan.model_validate({"id": "r", "room": ROOM, "objects": [
        {"id": i, "type": t, "size": {"x": w, "y": 1, "z": d}} for i, t, w, d in OBJECTS]})
    placements = [Placement(id=i, type=t, x=poses[i][0], z=poses[i][1], rotation=poses[i][2], size=Size(x=w, y=1, z=d))
                  for i, t, w, d in OBJECTS if i in poses]
    return plan, Layout(plan_id="r", solver="t", seed=0, placements=placements, timing=Timing(total_s=0, per_object_s=0))


def test_the_judge_and_the_prior_are_fitted_on_different_rooms():
    assert resources.files("models").joinpath("data/realism_stats.json").read_text() == build()
    judged = set(stats()["scenes"])
    assert len(judged) == 28 and all(judge_scene(s) for s in judged)


def test_a_bed_against_the_wall_with_its_side_table_is_human_like():
    human = realism(*scored({"bed": (2.0, 3.0, 180), "side": (0.95, 3.7, 180)}))  # head on the north wall
    facing_wall = realism(*scored({"bed": (2.0, 3.0, 0), "side": (0.95, 3.7, 180)}))
    floating = realism(*scored({"bed": (2.0, 2.0, 180), "side": (3.6, 0.4, 0)}))
    assert human == 1.0 and facing_wall < human and floating < facing_wall


def test_leaving_objects_out_fails_their_checks():
    passed, total = realism_checks(*scored({}))
    assert total > 0 and passed == 0
    assert realism(*scored({"bed": (2.0, 3.0, 180)})) < realism(*scored({"bed": (2.0, 3.0, 180),
                                                                         "side": (0.95, 3.7, 180)}))


def test_in_a_corner_facing_away_from_either_wall_counts_as_against_the_wall():
    """Both walls of a corner are touched at distance 0 (up to float noise): facing away from either is
    the wall habit kept; facing into either wall is not."""
    corner = {180: (0.7, 3.0), 90: (1.0, 3.3), 0: (0.7, 3.0), 270: (1.0, 3.3)}  # west and north walls touched
    passed = {r: realism_checks(*scored({"bed": (x, z, r)}))[0] for r, (x, z) in corner.items()}
    assert passed == {180: 1, 90: 1, 0: 0, 270: 0}


def test_each_check_names_its_object_kind_and_companion():
    plan, layout = scored({"bed": (2.0, 3.0, 180), "side": (3.6, 0.4, 0)})  # the side table far from the bed
    found = checks(plan, layout)
    assert (sum(c.passed for c in found), len(found)) == realism_checks(plan, layout)
    assert Check("bed", "wall", True) in found
    assert Check("side", "companion", False, "Bed") in found
