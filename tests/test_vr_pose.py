"""The VR start pose: on a circle around the anchor, clear of walls and objects, reaching and seeing it."""

from __future__ import annotations

import math

from interaction_scenes import COOL, LOOK, SIMPLE, graph, kitchen, obj
from shapely.geometry import LineString, Point

from models.interaction import vr_start_pose
from models.geometry import front
from models.interaction.vr_pose import (ARM_REACH, BODY_RADIUS, _sight_blocker, circle_radius, footprint,
                                         usable_face)
from models.values import AgentPose, Opening, Room, Scene


def room_with(objects, task, width=4.0, depth=4.0) -> Scene:
    room = Room(type="kitchen", width=width, depth=depth, doors=[Opening(wall="south", center=2.0, width=1.0)])
    return Scene(id="t", room=room, task_graph=task, objects=objects, robot_start=AgentPose(x=2, z=0.6, rotation=0))


def test_counter_against_a_wall_gets_a_pose_in_front_facing_it():
    counter = obj("countertop-0", "CounterTop", 2.0, 0.5, 0, "anchor")  # front faces +z, into the room
    choice = vr_start_pose(room_with([counter], SIMPLE))
    pose = choice.best
    assert pose is not None and choice.anchor_id == "countertop-0"
    front_z = 0.5 + counter.size.z / 2
    assert pose.z - front_z >= BODY_RADIUS - 1e-6  # the body clears the counter
    assert Point(pose.x, pose.z).distance(usable_face(counter, counter)) <= ARM_REACH + 1e-6
    assert abs(pose.rotation - 180) < 30  # looking at the counter (-z)
    assert 0 < pose.horizon < 60  # looking down at its top
    # ranked by distance to the room centre, best first
    d = [c.distance_to_room_centre for c in choice.alternatives]
    assert d == sorted(d) and len(d) >= 2
    assert choice.alternatives[0].pose == pose


def test_every_alternative_is_valid_by_an_independent_check():
    scene = kitchen(COOL)
    choice = vr_start_pose(scene)
    assert choice.best is not None
    for c in choice.alternatives:
        body = Point(c.pose.x, c.pose.z).buffer(BODY_RADIUS)
        assert body.bounds[0] >= 0 and body.bounds[1] >= 0 and body.bounds[2] <= 5 and body.bounds[3] <= 5
        assert all(not body.intersects(footprint(o).polygon()) for o in scene.objects)


def test_a_pose_is_checked_as_it_is_stored_rounded_to_the_millimetre():
    """A stool 0.17 mm further than a body radius from a candidate's exact position, and nearer than it from
    the position rounded as the pose stores it: the candidate must be rejected, not stored touching the stool."""
    counter = obj("countertop-0", "CounterTop", 2.0, 0.3055, 0, "anchor")
    ring, (dx, dz) = circle_radius(counter, counter), front(35.0)  # a candidate whose x rounds up by 0.34 mm
    px, pz = counter.x + ring * dx, counter.z + ring * dz
    assert round(px, 3) - px > 0.0003
    stool = obj("stool-0", "Stool", 0, 0, 0)
    stool = stool.model_copy(update={"x": px + BODY_RADIUS + 0.00017 + stool.size.x / 2, "z": pz})
    choice = vr_start_pose(room_with([counter, stool], SIMPLE, width=5.0))
    assert choice.alternatives
    for c in choice.alternatives:
        assert footprint(stool).polygon().distance(Point(c.pose.x, c.pose.z)) >= BODY_RADIUS


def test_stools_in_front_push_the_pose_to_a_gap_or_report_why():
    counter = obj("countertop-0", "CounterTop", 2.0, 0.5, 0, "anchor")
    front_z = 0.5 + counter.size.z / 2
    # a row of shelving units all along the counter's front: no way to stand and reach it
    wall = [obj(f"shelvingunit-{i}", "ShelvingUnit", 0.25 + 0.43 * i, front_z + 0.3, 0) for i in range(9)]
    choice = vr_start_pose(room_with([counter, *wall], SIMPLE))
    assert choice.best is None and choice.alternatives == []
    assert choice.reasons and "no valid pose" in choice.reasons[0]
    assert sum(choice.rejected.values()) == choice.candidates_tried


def test_a_tall_object_blocks_the_line_of_sight_a_low_one_does_not():
    tall = [("shelf", LineString([(0.9, -0.2), (1.1, -0.2), (1.1, 0.2), (0.9, 0.2)]).convex_hull, 2.0)]
    low = [("stool", tall[0][1], 0.3)]
    target = (2.0, 0.9, 0.0)
    assert _sight_blocker((0.0, 0.0), target, tall) == "shelf"
    assert _sight_blocker((0.0, 0.0), target, low) is None


def test_no_anchor_or_unplaced_anchor_gives_no_pose_with_a_reason():
    no_anchor = graph("pick_and_place_simple", [("Apple", "placed_at", "CounterTop")],
                      {"Apple": ["key"], "CounterTop": ["key"]})
    assert vr_start_pose(kitchen(no_anchor)).best is None
    assert "no anchor" in vr_start_pose(kitchen(no_anchor)).reasons[0]
    choice = vr_start_pose(kitchen(LOOK, drop=("FloorLamp",)))
    assert choice.best is None and "not in the scene" in choice.reasons[0]


def test_child_anchor_pose_stands_in_front_of_its_holder():
    task = graph("look_at_obj_in_light", [("Book", "examined_under", "DeskLamp")],
                 {"Book": ["key"], "DeskLamp": ["key", "anchor"]})
    desk = obj("desk-0", "Desk", 2.0, 3.6, 180, children=(obj("desklamp-0", "DeskLamp", 2.3, 3.35, 180, "anchor",
                                                              y=0.9),))
    choice = vr_start_pose(room_with([desk], task))
    assert choice.anchor_id == "desklamp-0" and choice.best is not None
    assert choice.best.z < 3.6 - desk.size.z / 2  # in front of the desk (its front faces -z)
    lamp = desk.children[0]
    heading = math.degrees(math.atan2(lamp.x - choice.best.x, lamp.z - choice.best.z)) % 360
    assert abs(heading - choice.best.rotation) < 0.2


def test_assembled_scenes_carry_the_best_pose_and_alternatives():
    from app.pipeline import Pipeline
    gen = Pipeline(solver="dfs").generate("Put a chilled bread on the counter", "kitchen", seed=0)
    choice = vr_start_pose(gen.scene)
    assert gen.scene.vr_anchor == choice.best
    assert gen.scene.vr_alternatives == [c.pose for c in choice.alternatives[1:]]


def test_benchmark_audit_rejects_what_it_should():
    from app.bench.vrpose import audit
    counter = obj("countertop-0", "CounterTop", 2.0, 0.5, 0, "anchor")
    shelf = obj("shelvingunit-0", "ShelvingUnit", 2.0, 1.6, 0)  # tall, between the pose below and the counter
    scene = room_with([counter, shelf], SIMPLE)
    assert audit(scene, None) == "no pose"
    assert audit(scene, AgentPose(x=2.0, z=0.1, rotation=180)) == "body crosses a wall"
    assert audit(scene, AgentPose(x=2.0, z=0.9, rotation=180)).startswith("body collides with countertop-0")
    assert audit(scene, AgentPose(x=2.0, z=2.2, rotation=180)) == "anchor out of arm's reach"
    blocked = room_with([counter, obj("shelvingunit-0", "ShelvingUnit", 2.0, 1.005, 0)], SIMPLE)
    pose = AgentPose(x=2.0, z=1.5, rotation=180, horizon=34)
    assert audit(room_with([counter], SIMPLE), pose) is None
    assert audit(blocked, pose) == "line of sight blocked by shelvingunit-0"
    assert vr_start_pose(blocked).best is None or audit(blocked, vr_start_pose(blocked).best) is None
    assert audit(room_with([counter], SIMPLE), pose.model_copy(update={"rotation": 0})) == \
        "anchor outside the horizontal field of view"
    choice = vr_start_pose(scene)
    assert choice.best is not None and audit(scene, choice.best) is None
