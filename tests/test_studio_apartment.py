"""The studio's apartment mode in chromium: the whole house with room labels, the robot's path, the step
animation room by room, accept & save as versions, downloads by version; a single room afterwards leaves
the apartment mode, and reopening the stored apartment shows the whole house again. A room of the apartment
is edited like a single room (a click picks the room; constraint text, typed pose, re-place the rest, undo),
each edit folded back into the house; a task-graph correction regenerates the whole apartment; an object typed
or dragged onto another room's floor is carried there."""

import json
import re
from pathlib import Path

import numpy as np
import pytest
from studio_support import (SCREENSHOTS, VIEWPORT, WAIT, browser, choose, close_tabs, dismiss_notices, enter,  # noqa: F401
                            field, open_studio, screen_xy, session_of, settle, studio, wait_until)

pytest.importorskip("playwright")

from app.pipeline import room_generation  # noqa: E402
from frontend.apartment import ApartmentMode, first_room  # noqa: E402
from frontend.camera import PANEL_PX, room_points  # noqa: E402
from frontend.graph_image import render as render_graph  # noqa: E402
from frontend.replay import energy_after_steps, room_at  # noqa: E402
from frontend.view import world  # noqa: E402


def _three_rooms(browser, studio):
    """A new tab and its session, showing a kitchen, a living room and a bedroom (seed 4: an apartment whose kitchen
    the robot reaches, so the path is drawn)."""
    before = set(studio.sessions)
    page = open_studio(browser, studio)
    session = session_of(studio, before)
    choose(page, "Room type", "apartment", session.room)
    enter(page, "Rooms (apartment)", "kitchen, living room, bedroom", session.rooms)
    enter(page, "Seed", 4, session.seed)
    page.get_by_role("button", name="Generate").click()
    page.get_by_text("Apartment ready").wait_for(timeout=WAIT)
    return page, session


def _placed(studio, session) -> list:
    """The placer's own steps for `_three_rooms`' apartment (each in its room's frame, as the energy is measured)."""
    steps = []
    studio.pipeline.generate_apartment(session.instruction.value, ["kitchen", "living room", "bedroom"], 4,
                                       session.state.solver, steps.append)
    return steps


def _saved(page, studio, session, name: str, apartment) -> list[str]:
    """*Accept & save* of the apartment on screen as a new scene (confirming over failed checks, as a designer
    would); checks that the store holds `apartment` and returns the kinds of its edit log."""
    page.get_by_role("tab", name="Scenes").click()
    enter(page, "Name", name, session.scenes.save_name)
    page.get_by_role("button", name="Accept & save").click()
    if session.apartment.findings():
        page.get_by_role("button", name="Save anyway").click()
    saved = page.get_by_text(re.compile(r"Saved as scene \d+, version 1"))
    saved.wait_for(timeout=WAIT)
    scene_id = int(re.search(r"scene (\d+)", saved.inner_text()).group(1))
    assert studio.store.scene(scene_id, 1) == apartment
    return [e["kind"] for e in studio.store.edits(scene_id)]


def test_apartment_in_the_studio(browser, studio):  # noqa: F811
    page, session = _three_rooms(browser, studio)
    apartment = session.apartment.current
    assert apartment.key_nav == 1.0
    wait_until(page, lambda: len(session.placement.energy_plot.data[0]) == len(session.state.steps),
               "the energy plot of the apartment's steps")  # not the room generated before
    placed = _placed(studio, session)
    rooms = [(plan, layout.placements) for plan, layout in zip(apartment.plans, apartment.layouts)]
    total = [round(r["total"], 4) for r in energy_after_steps(rooms, placed, ApartmentMode.room_of)]
    assert list(session.placement.energy_plot.data[-1]) == total
    assert [hr.room.type for hr in apartment.floorplan.rooms] == ["kitchen", "living room", "bedroom"]
    nodes = {h._impl.name for h in session.view.nodes}
    assert {"/rooms/1. kitchen", "/rooms/2. living room", "/rooms/3. bedroom", "/markers/path"} <= nodes
    assert {f"/room/{k}/floor" for k in (1, 2, 3)} <= nodes
    assert set(session.view.objects) == {o.id for o in session.displayed().all_objects()}
    page.get_by_text("Key_NAV through the doors").wait_for(timeout=WAIT)
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SCREENSHOTS / "apartment.png"))
    page.get_by_role("button", name="Top view").click()
    dismiss_notices(page)
    page.wait_for_timeout(1500)
    page.screenshot(path=str(SCREENSHOTS / "apartment-top.png"))  # the README's picture (docs/apartment-studio.png)

    fridge = next(o for o in session.displayed().objects if o.type == "Fridge")
    session.picking.pick(fridge.id)  # the gizmo on its top, where it stands in the house
    assert session.picking.picked.visible and fridge.id in session.picking.picked_md.content
    assert np.allclose(session.picking.controls.position[::2], world(fridge.x, 0, fridge.z)[::2], atol=1e-3)
    session.placement.animate("Step")  # from the start: the first room's first object
    assert "room 1 / 3 (kitchen)" in session.placement.step_md.content
    rooms_in_order = []
    while session.state.shown < len(session.state.steps):
        session.placement.advance()
        rooms_in_order.append(session.placement.step_md.content.split("room ")[1][0])
        house, visible = room_at(session.displayed(), session.state.steps, session.state.shown, ApartmentMode.room_of)
        on_show = {oid for oid, h in session.view.objects.items() if h.visible}
        assert on_show == (visible if visible is not None else set(session.view.objects))
        step = session.state.steps[session.state.shown - 1]
        for o in house.objects if step.x is not None else ():  # the object it placed stands where the step put it
            if o.id == step.object_id:
                assert np.allclose(session.view.objects[o.id].position, world(o.x, o.y, o.z)), o.id
    assert rooms_in_order == sorted(rooms_in_order) and rooms_in_order[-1] == "3"  # room by room

    steps = len(session.state.steps)

    page.get_by_role("tab", name="Scenes").click()
    field(page, "Name").fill("three rooms")
    page.get_by_role("button", name="Accept & save").click()
    saved = page.get_by_text(re.compile(r"Saved as scene \d+, version 1"))
    saved.wait_for(timeout=WAIT)
    scene_id = int(re.search(r"scene (\d+)", saved.inner_text()).group(1))
    assert studio.store.scene(scene_id, 1) == apartment
    assert field(page, "Stored scene").input_value().startswith(f"{scene_id}:")
    with page.expect_download() as download:
        page.get_by_role("button", name="Download house JSON").click()
    assert download.value.suggested_filename == "three-rooms-v1-house.json"
    assert [r["id"] for r in json.loads(Path(download.value.path()).read_text())["rooms"]] == \
        ["room|1", "room|2", "room|3"]

    page.get_by_role("tab", name="Task").click()
    choose(page, "Room type", "kitchen")
    page.get_by_role("button", name="Generate").click()
    page.get_by_text("Scene ready").wait_for(timeout=WAIT)
    assert session.apartment.current is None and session.state.gen is not None

    page.get_by_role("tab", name="Scenes").click()
    choose(page, "Stored scene", f"{scene_id}: three rooms")
    page.get_by_role("button", name="Open").click()
    page.get_by_text(re.compile(rf"Opened scene {scene_id}, version 1")).wait_for(timeout=WAIT)
    assert session.apartment.current == apartment
    assert session.state.gen.plan == apartment.plans[first_room(apartment)]  # the room edited first
    assert {"/rooms/1. kitchen", "/rooms/3. bedroom", "/markers/path"} <= {h._impl.name for h in session.view.nodes}
    assert len(session.state.steps) == steps  # each room's placer replayed with the stored seed
    page.get_by_role("button", name="Accept & save").click()  # the reopened apartment's next version
    page.get_by_text(re.compile(rf"Saved as scene {scene_id}, version 2")).wait_for(timeout=WAIT)
    assert [v["number"] for v in studio.store.versions(scene_id)] == [1, 2]


def test_editing_a_room_of_an_apartment(browser, studio):  # noqa: F811
    page, session = _three_rooms(browser, studio)
    dismiss_notices(page)
    first = session.apartment.current
    assert session.state.values.room == 0 and session.state.gen.plan == first.plans[0]  # the counter's kitchen
    page.get_by_role("tab", name="Constraints").click()
    page.get_by_text("Editing room 1 (kitchen) of the apartment").wait_for(timeout=WAIT)

    bed = next(o for o in session.displayed().objects if o.type == "Bed")
    session.state.busy = True  # while a re-plan of the kitchen runs, a click elsewhere does not change the room
    session.picking.pick(bed.id)
    assert session.state.values.room == 0 and session.picking.controls is None
    session.state.busy = False

    # a real click on the living room's sofa makes the living room the room edited
    page.get_by_role("button", name="Top view").click()
    wait_until(page, lambda: session.state.view == "top", "the top view")
    moved_at = session.client.camera.update_timestamp
    wait_until(page, lambda: session.client.camera.update_timestamp > moved_at, "the browser's camera looking down")
    settle(page, 6)
    sofa = next(o for o in session.displayed().objects if o.type == "Sofa")
    page.mouse.click(*screen_xy(session, world(sofa.x, sofa.y + sofa.size.y / 2, sofa.z)))
    wait_until(page, lambda: session.picking.selected == sofa.id, "the picked sofa")
    page.get_by_text("Editing room 2 (living room) of the apartment").wait_for(timeout=WAIT)
    assert session.state.values.room == 1 and set(session.constraints.object.options) == \
        {o.id for o in first.plans[1].objects}
    assert session.picking.controls is not None
    page.get_by_role("button", name="Fit room").click()  # frames the room edited, not the house
    wait_until(page, lambda: session.state.view == "room", "the living room framed")
    living, free = first.floorplan.rooms[1], VIEWPORT["width"] - PANEL_PX

    def living_room_framed() -> bool:  # the browser may report a camera update sent before the new view reached it
        floor = room_points(living.room.width, living.room.depth, 0.0) + world(living.x, 0.0, living.z)
        corners = np.array([screen_xy(session, p) for p in floor])
        inside = (corners[:, 0] >= 0).all() and (corners[:, 0] <= free).all() and (corners[:, 1] >= 0).all()
        fills = np.ptp(corners[:, 0]) > 0.8 * free or np.ptp(corners[:, 1]) > 0.8 * VIEWPORT["height"]
        return bool(inside and fills)  # it fills the free area (framing the house, it fills about 0.6 of it)
    wait_until(page, living_room_framed, "the living room filling the free area")

    # a constraint edit re-places the living room only, as the pipeline re-plans that room alone
    original = field(page, "Raw constraints").input_value()
    assert original == first.plans[1].constraints
    edited = re.sub(rf"{sofa.id} \| [^\n]*", f"{sofa.id} | middle", original)
    assert edited != original
    enter(page, "Raw constraints", edited, session.constraints.text)
    page.get_by_role("button", name="Apply text").click()
    page.get_by_text(re.compile("Re-placed after the edit")).wait_for(timeout=WAIT)
    edited_apartment = session.apartment.current
    replanned = []
    expected = studio.pipeline.replan(room_generation(first, 1), edited, 4, session.state.solver, replanned.append)
    assert edited_apartment.layouts[1].placements == expected.layout.placements
    assert edited_apartment.plans[1].constraints == edited
    assert [edited_apartment.layouts[k] for k in (0, 2)] == [first.layouts[k] for k in (0, 2)]
    steps = session.state.steps  # the house's steps: the living room's new ones where its old ones were
    rooms = [ApartmentMode.room_of(s.object_id) for s in steps]
    assert rooms == sorted(rooms) and sum(r == "r2" for r in rooms) >= len(expected.layout.placements)
    placed = _placed(studio, session)  # the energy plot: the other rooms' steps and the re-plan's
    house_steps = [s for s in placed if s.object_id.startswith("r1-")] + replanned + \
        [s for s in placed if s.object_id.startswith("r3-")]
    rooms = [(plan, layout.placements) for plan, layout in zip(edited_apartment.plans, edited_apartment.layouts)]
    total = [round(r["total"], 4) for r in energy_after_steps(rooms, house_steps, ApartmentMode.room_of)]
    wait_until(page, lambda: list(session.placement.energy_plot.data[-1]) == total, "the energy plot after the edit")
    offset = first.floorplan.rooms[1]
    for p in edited_apartment.layouts[1].placements:  # drawn in the house frame
        assert np.allclose(session.view.objects[p.id].position[::2],
                           world(p.x + offset.x, 0, p.z + offset.z)[::2], atol=1e-3), p.id

    # a typed pose is in the house frame, as the fields show it; the layout keeps the room's frame
    session.picking.pick(sofa.id)
    shown = next(o for o in session.displayed().objects if o.id == sofa.id)
    assert session.picking.pose_x.value == round(shown.x, 3)
    target = round(offset.x + offset.room.width / 2, 2)
    enter(page, "x (m)", target, session.picking.pose_x)
    page.get_by_role("button", name="Apply pose").click()
    page.get_by_text(re.compile(rf"Moved {sofa.id} to \({target:.2f}")).wait_for(timeout=WAIT)
    assert abs(session.state.gen.layout.placement(sofa.id).x - (target - offset.x)) < 1e-3
    assert abs(session.apartment.current.layouts[1].placement(sofa.id).x - (target - offset.x)) < 1e-3
    typed = session.state.gen.layout.placement(sofa.id)

    # a real drag of the gizmo's x arrow, in the house: the layout takes it in the room's frame
    settle(page, 6)
    top = np.asarray(session.picking.controls.position)
    arrow, shift = 0.5 * session.picking.controls.scale, 0.4
    page.mouse.move(*screen_xy(session, top + (arrow, 0, 0)))
    page.mouse.down()
    page.mouse.move(*screen_xy(session, top + (arrow + shift, 0, 0)), steps=15)
    page.mouse.up()
    wait_until(page, lambda: session.state.gen.layout.placement(sofa.id).x != typed.x, "the dragged sofa")
    dragged = session.state.gen.layout.placement(sofa.id)
    shown = next(o for o in session.displayed().objects if o.id == sofa.id)
    assert abs(dragged.x - typed.x - shift) < 0.15 and dragged.z == typed.z
    assert abs(shown.x - offset.x - dragged.x) < 1e-3 and abs(shown.z - offset.z - dragged.z) < 1e-3
    assert session.apartment.current.layouts[1].placement(sofa.id) == dragged
    moved = session.apartment.current

    page.get_by_role("button", name="Re-place the rest").click()
    page.get_by_text(re.compile(rf"Re-placed around {sofa.id}")).wait_for(timeout=WAIT)
    around = session.apartment.current
    assert around.layouts[1].placement(sofa.id) == moved.layouts[1].placement(sofa.id)
    assert [around.layouts[k] for k in (0, 2)] == [first.layouts[k] for k in (0, 2)]
    page.get_by_role("button", name="Undo").click()
    page.get_by_text("Undid: re-place the rest.").wait_for(timeout=WAIT)
    assert session.apartment.current is moved and session.state.gen.layout == moved.layouts[1]

    page.get_by_role("tab", name="Task").click()  # a task-graph correction regenerates the whole apartment
    page.get_by_text("Correct the task graph").click()
    choose(page, "Object", "Fridge", session.graph.object)
    page.get_by_role("button", name="Remove object").click()
    page.get_by_text(re.compile(r"Task graph edited \(-Fridge\).*rebuild the apartment")).wait_for(timeout=WAIT)
    corrected = session.state.gen.task_graph  # the fridge's relation goes with it: the graph's picture draws it
    assert corrected.relations and all("Fridge" not in (r[0], r[2]) for r in corrected.relations)
    assert render_graph(corrected).shape[2] == 3
    page.get_by_role("button", name="Regenerate from graph").click()
    page.get_by_text(re.compile("Apartment regenerated from the corrected graph")).wait_for(timeout=WAIT)
    again = session.apartment.current
    assert [hr.room.type for hr in again.floorplan.rooms] == ["kitchen", "living room", "bedroom"]
    assert "Fridge" not in {o.type for o in again.task_graph.objects} | {o.type for p in again.plans for o in p.objects
                                                                      if o.is_task}
    page.get_by_role("button", name="Undo").click()
    page.get_by_text("Undid: regenerate from graph.").wait_for(timeout=WAIT)
    assert session.apartment.current is moved

    # the Room edited dropdown makes another room the one edited without a click on one of its objects
    page.get_by_role("tab", name="Constraints").click()
    session.picking.pick(sofa.id)
    assert session.state.values.room == 1 and session.constraints.room.value == "room 2 (living room)"
    choose(page, "Room edited", "room 3 (bedroom)", session.constraints.room)
    page.get_by_text("Editing room 3 (bedroom) of the apartment").wait_for(timeout=WAIT)
    assert session.state.values.room == 2 and session.picking.selected is None  # the sofa is let go
    wait_until(page, lambda: field(page, "Raw constraints").input_value() == moved.plans[2].constraints,
               "the bedroom's constraints")

    kinds = _saved(page, studio, session, "edited flat", moved)  # the moved sofa may fail a check
    assert kinds[:7] == ["constraints", "move", "move", "re-place", "undo", "task-graph", "undo"]
    assert set(kinds[7:]) <= {"override"}


def test_an_object_put_into_another_room_is_carried_there(browser, studio):  # noqa: F811
    page, session = _three_rooms(browser, studio)
    dismiss_notices(page)
    first = session.apartment.current
    wait_until(page, lambda: len(session.placement.energy_plot.data[0]) == len(session.state.steps),
               "the energy plot of the apartment's steps")
    table = next(o for o in first.plans[0].objects if o.holds)  # what the bread stands on, in the kitchen
    session.picking.pick(table.id)
    living = first.floorplan.rooms[1]
    x, z = round(living.x + living.room.width / 2, 2), round(living.z + living.room.depth / 2, 2)
    enter(page, "x (m)", x, session.picking.pose_x)
    enter(page, "z (m)", z, session.picking.pose_z)
    page.get_by_role("button", name="Apply pose").click()
    page.get_by_text(re.compile(rf"Carried {table.id} into room 2 \(living room\) as r2-")).wait_for(timeout=WAIT)

    carried = session.apartment.current
    new_id = session.picking.selected
    assert new_id.startswith("r2-") and session.state.values.room == 1 and session.state.gen.plan == carried.plans[1]
    put = carried.layouts[1].placement(new_id)
    assert (put.x, put.z) == pytest.approx((x - living.x, z - living.z), abs=1e-3)
    assert table.id not in {o.id for p in carried.plans for o in p.objects}
    assert carried.plan.assignment["Bread"] == living.id and new_id in carried.path.visits
    assert table.id not in session.view.objects and np.allclose(session.view.objects[new_id].position[::2],
                                                                world(x, 0, z)[::2], atol=1e-3)
    assert table.id not in {s.object_id for s in session.state.steps}
    rooms = [(plan, layout.placements) for plan, layout in zip(carried.plans, carried.layouts)]
    placed = [s for s in _placed(studio, session) if s.object_id != table.id]
    total = [round(r["total"], 4) for r in energy_after_steps(rooms, placed, ApartmentMode.room_of)]
    wait_until(page, lambda: list(session.placement.energy_plot.data[-1]) == total, "the energy plot after the carry")
    edit = session.state.edits[-1]
    assert (edit.kind, edit.target, edit.after["room"], edit.after["id"]) == ("carry", table.id, 2, new_id)

    page.get_by_role("button", name="Undo").click()
    page.get_by_text(f"Undid: carry {table.id}.").wait_for(timeout=WAIT)
    assert session.apartment.current is first and session.state.values.room == 0
    assert table.id in session.view.objects and new_id not in session.view.objects
    assert session.picking.selected == table.id  # still picked, by its id before the carry
    page.get_by_role("button", name="Redo").click()
    page.get_by_text(f"Redid: carry {table.id}.").wait_for(timeout=WAIT)
    assert session.apartment.current is carried and new_id in session.view.objects
    assert session.picking.selected == new_id and session.state.values.room == 1

    # the room it went to is edited like any other: re-placed around it, then saved with the carry in the log
    page.get_by_role("button", name="Re-place the rest").click()
    page.get_by_text(re.compile(rf"Re-placed around {new_id}")).wait_for(timeout=WAIT)
    around = session.apartment.current
    assert around.layouts[1].placement(new_id) == put and around.layouts[0] == carried.layouts[0]
    kinds = _saved(page, studio, session, "carried table", around)
    assert kinds[:4] == ["carry", "undo", "redo", "re-place"] and set(kinds[4:]) <= {"override"}


def test_a_drag_through_the_wall_says_it_will_carry_and_carries_on_release(browser, studio):  # noqa: F811
    page, session = _three_rooms(browser, studio)
    dismiss_notices(page)
    first = session.apartment.current

    def beyond(o) -> float:  # metres along x (house frame) to the nearest other room's floor, 0: none within 1.5 m
        for d in np.arange(0.1, 1.5, 0.05):
            for shift in (d, -d):
                if session.apartment.room_at(o.x + shift, o.z) not in (None, 0):
                    return float(shift + 0.3 * np.sign(shift))
        return 0.0
    shown = [o for o in session.displayed().objects if o.id.startswith("r1-") and beyond(o)]
    obj = min(shown, key=lambda o: abs(beyond(o)))
    shift = beyond(obj)
    to = session.apartment.room_at(obj.x + shift, obj.z)
    page.get_by_role("button", name="Top view").click()
    wait_until(page, lambda: session.state.view == "top", "the top view")
    settle(page, 6)
    session.picking.pick(obj.id)
    settle(page, 4)
    top = np.asarray(session.picking.controls.position)
    arrow = 0.5 * session.picking.controls.scale  # the x arrow points along +x: grabbed there, dragged either way
    page.mouse.move(*screen_xy(session, top + (arrow, 0, 0)))
    page.mouse.down()
    page.mouse.move(*screen_xy(session, top + (arrow + shift, 0, 0)), steps=20)
    label = session.apartment.label(to)
    wait_until(page, lambda: "Release to carry" in session.checks_md.content, "the carry announced while dragging")
    assert label in session.checks_md.content and session.apartment.current is first  # nothing carried yet
    page.mouse.up()
    page.get_by_text(re.compile(rf"Carried {obj.id} into {re.escape(label)} as r{to + 1}-")).wait_for(timeout=WAIT)
    carried = session.apartment.current
    assert obj.id not in {o.id for p in carried.plans for o in p.objects}
    assert session.state.values.room == to and session.picking.selected in {o.id for o in carried.plans[to].objects}
