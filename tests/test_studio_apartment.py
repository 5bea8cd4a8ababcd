"""The studio's apartment mode in chromium: the whole house with room labels, the robot's path, the step
animation room by room, accept & save as versions, downloads by version; a single room afterwards leaves
the apartment mode, and reopening the stored apartment shows the whole house again."""

import json
import re
from pathlib import Path

import numpy as np
import pytest
from studio_support import (SCREENSHOTS, WAIT, browser, choose, close_tabs, dismiss_notices, enter,  # noqa: F401
                            field, open_studio, session_of, studio, wait_until)

pytest.importorskip("playwright")

from frontend.apartment import ApartmentMode  # noqa: E402
from frontend.replay import room_at  # noqa: E402
from frontend.view import world  # noqa: E402


def test_apartment_in_the_studio(browser, studio):  # noqa: F811
    before = set(studio.sessions)
    page = open_studio(browser, studio)
    session = session_of(studio, before)
    choose(page, "Room type", "apartment", session.room)
    enter(page, "Rooms (apartment)", "kitchen, living room, bedroom", session.rooms)
    enter(page, "Seed", 4, session.seed)  # an apartment whose kitchen the robot reaches (the path is drawn)
    page.get_by_role("button", name="Generate").click()
    page.get_by_text("Apartment ready").wait_for(timeout=WAIT)
    apartment = session.apartment.current
    assert apartment.key_nav == 1.0
    wait_until(page, lambda: len(session.energy_plot.data[0]) == len(session.state.steps),
               "the energy plot of the apartment's steps")  # not the room generated before
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

    fridge = next(o.id for o in session.displayed().objects if o.type == "Fridge")
    session.pick(fridge)  # inspected, not movable: no drag gizmo
    assert session.picked.visible and fridge in session.picked_md.content and session.controls is None
    session.animate("Step")  # from the start: the first room's first object
    assert "room 1 / 3 (kitchen)" in session.step_md.content
    rooms_in_order = []
    while session.state.shown < len(session.state.steps):
        session._advance()
        rooms_in_order.append(session.step_md.content.split("room ")[1][0])
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
    assert session.apartment.current == apartment and session.state.gen is None
    assert {"/rooms/1. kitchen", "/rooms/3. bedroom", "/markers/path"} <= {h._impl.name for h in session.view.nodes}
    assert len(session.state.steps) == steps  # each room's placer replayed with the stored seed
    page.get_by_role("button", name="Accept & save").click()  # the reopened apartment's next version
    page.get_by_text(re.compile(rf"Saved as scene {scene_id}, version 2")).wait_for(timeout=WAIT)
    assert [v["number"] for v in studio.store.versions(scene_id)] == [1, 2]
