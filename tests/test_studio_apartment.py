"""The studio's apartment mode in chromium: the whole house with room labels, the robot's path, the step
animation room by room, downloads; a single room afterwards leaves the apartment mode."""

import pytest
from studio_support import SCREENSHOTS, WAIT, browser, choose, field, open_studio, session_of, studio  # noqa: F401

pytest.importorskip("playwright")


def test_apartment_in_the_studio(browser, studio):  # noqa: F811
    before = set(studio.sessions)
    page = open_studio(browser, studio)
    session = session_of(studio, before)
    choose(page, "Room type", "apartment")
    field(page, "Rooms (apartment)").fill("kitchen, living room, bedroom")
    field(page, "Seed").fill("4")  # an apartment whose kitchen the robot reaches (the path is drawn)
    page.get_by_role("button", name="Generate").click()
    page.get_by_text("Apartment ready").wait_for(timeout=WAIT)
    apartment = session.apartment.current
    assert apartment.key_nav == 1.0
    assert [hr.room.type for hr in apartment.floorplan.rooms] == ["kitchen", "living room", "bedroom"]
    nodes = {h._impl.name for h in session.view.nodes}
    assert {"/rooms/1. kitchen", "/rooms/2. living room", "/rooms/3. bedroom", "/markers/path"} <= nodes
    assert {f"/room/{k}/floor" for k in (1, 2, 3)} <= nodes
    assert set(session.view.objects) == {o.id for o in session.displayed().all_objects()}
    page.get_by_text("Key_NAV through the doors").wait_for(timeout=WAIT)
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SCREENSHOTS / "apartment.png"))
    page.get_by_role("button", name="Top view").click()
    close = page.locator(".mantine-Notification-root button")  # viser's "software WebGL" notice
    if close.count():
        close.first.click()
    page.wait_for_timeout(1500)
    page.screenshot(path=str(SCREENSHOTS / "apartment-top.png"))  # the README's picture (docs/apartment-studio.png)

    fridge = next(o.id for o in session.displayed().objects if o.type == "Fridge")
    session.pick(fridge)  # inspected, not movable: no drag gizmo
    assert session.picked.visible and fridge in session.picked_md.content and session.controls is None
    session.accept()
    assert "cannot be stored" in session.status.content

    session.animate("Step")  # from the start: the first room's first object
    assert "room 1 / 3 (kitchen)" in session.step_md.content
    rooms_in_order = []
    while session.state.shown < len(session.state.steps):
        session._advance()
        rooms_in_order.append(session.step_md.content.split("room ")[1][0])
    assert rooms_in_order == sorted(rooms_in_order) and rooms_in_order[-1] == "3"  # room by room

    choose(page, "Room type", "kitchen")
    page.get_by_role("button", name="Generate").click()
    page.get_by_text("Scene ready").wait_for(timeout=WAIT)
    assert session.apartment.current is None and session.state.gen is not None
