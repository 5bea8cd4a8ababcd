"""The studio as a daily tool, in a real browser with real mouse events: the camera keeps the room in
view, a drag into a collision is flagged and saving it asks first, undo restores the pose, downloads are
the selected version and furniture is drawn and exported as shapes, not boxes."""

import io
import json
import math
import re
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from studio_support import (  # noqa: F401 (browser, close_tabs and studio are fixtures)
    _OPENED, VIEWPORT, WAIT, browser, choose, close_tabs, enter, field, generate, object_xy, open_studio, screen_xy,
    session_of, settle, studio, wait_until)

from frontend.camera import PANEL_PX, room_points
from models.exports.procthor_house import to_house
from models.shapes import family_of

pytest.importorskip("playwright.sync_api")


def floor_like(rgb: np.ndarray) -> np.ndarray:
    """Pixels of the lit floor colour (warm light grey): red >= green >= blue, a little warmer than grey."""
    r, g, b = (rgb[..., i].astype(int) for i in range(3))
    return (r >= g) & (g >= b) & (r - b >= 12) & (r - b <= 60) & (r > 90)


def floor_corners(session, room) -> np.ndarray:
    """Screen positions of the room's floor corners, seen by the tab's camera."""
    return np.array([screen_xy(session, p) for p in room_points(room.width, room.depth, 0.0)])


def test_room_in_view_after_orbit_and_generate(browser, studio):
    before = set(studio.sessions)
    page = open_studio(browser, studio)
    session = session_of(studio, before)
    generate(page, session, "Put a chilled bread on the counter", "kitchen", run=1)
    settle(page)
    page.mouse.move(300, 700)  # orbit and zoom with the real mouse, far from the room's framing
    page.mouse.down()
    page.mouse.move(650, 420, steps=12)
    page.mouse.up()
    for _ in range(6):
        page.mouse.wheel(0, -400)
    settle(page)
    generate(page, session, "Look at the book under the desk lamp", "bedroom", run=2)
    settle(page, 6)
    width, height = page.viewport_size["width"], page.viewport_size["height"]
    free = width - PANEL_PX
    room = session.state.gen.scene.room
    corners = floor_corners(session, room)
    assert (corners[:, 0] >= 0).all() and (corners[:, 0] <= free).all(), corners
    assert (corners[:, 1] >= 0).all() and (corners[:, 1] <= height).all(), corners
    shot = np.asarray(Image.open(io.BytesIO(page.screenshot())).convert("RGB"))
    floor = floor_like(shot[:, :free])
    assert floor.mean() > 0.08, f"only {100 * floor.mean():.1f} % of the free area shows floor"
    ys, xs = np.nonzero(floor)
    assert free * 0.25 < xs.mean() < free * 0.75 and height * 0.25 < ys.mean() < height * 0.75
    assert floor_like(shot[:, free + 20:]).mean() < 0.02  # the room is not under the panel

    page.get_by_role("button", name="Top view").click()
    wait_until(page, lambda: session.state.view == "top", "the top view")
    settle(page)
    corners = floor_corners(session, room)
    assert (corners[:, 0] <= free).all() and (corners[:, 1] >= 0).all()
    assert page.evaluate("() => window.__viserMutable.cameraControl.maxPolarAngle") < math.pi / 2  # above floor

    page.set_viewport_size({"width": 1000, "height": 760})  # a smaller window: the room is framed again
    wait_until(page, lambda: session.state.canvas == (1000, 760), "a refit after the resize")

    def framed() -> bool:  # the browser may report a camera update sent before the refit reached it
        corners = floor_corners(session, room)
        return bool((corners[:, 0] >= 0).all() and (corners[:, 0] <= 1000 - PANEL_PX).all()
                    and (corners[:, 1] <= 760).all())
    wait_until(page, framed, "the room's floor inside the smaller window, left of the panel")


def test_a_hidpi_screen_frames_the_room_beside_the_panel_and_clicks_pick(browser, studio):
    """With two device pixels per CSS pixel the camera's drawing buffer is twice the page's size, while the panel
    and the mouse are in CSS pixels: the page reports its CSS size, and the room is framed in the free part."""
    before = set(studio.sessions)
    context = browser.new_context(viewport=VIEWPORT, device_scale_factor=2)
    _OPENED.append(context)
    page = context.new_page()
    page.goto(f"http://127.0.0.1:{studio.port}")
    page.get_by_role("button", name="Generate").wait_for(timeout=WAIT)
    session = session_of(studio, before)
    wait_until(page, lambda: session.canvas() == (VIEWPORT["width"], VIEWPORT["height"]), "the page's CSS size")
    generate(page, session, "Put a chilled bread on the counter", "kitchen")
    settle(page, 6)
    assert session.client.camera.image_width > VIEWPORT["width"]  # the drawing buffer: device pixels
    free = VIEWPORT["width"] - PANEL_PX
    corners = floor_corners(session, session.state.gen.scene.room)
    assert (corners[:, 0] >= 0).all() and (corners[:, 0] <= free).all(), corners
    shot = np.asarray(Image.open(io.BytesIO(page.screenshot())).convert("RGB"))  # device pixels
    scale = shot.shape[1] / VIEWPORT["width"]
    assert scale == 2 and floor_like(shot[:, :int(free * scale)]).mean() > 0.08
    assert floor_like(shot[:, int((free + 20) * scale):]).mean() < 0.02  # the room is not under the panel
    page.mouse.click(*object_xy(session, "fridge-0"))  # a click where the fridge is drawn picks it
    wait_until(page, lambda: session.picking.selected == "fridge-0", "the picked fridge")


def test_drag_into_collision_warns_asks_before_saving_and_undo_restores(browser, studio):
    before = set(studio.sessions)
    page = open_studio(browser, studio)
    session = session_of(studio, before)
    generate(page, session, "Put a chilled bread on the counter", "kitchen")
    settle(page)
    fridge = session.state.gen.layout.placement("fridge-0")
    counter = session.state.gen.layout.placement("countertop-0")
    placed_findings = list(session.state.findings)  # what the placer left, before any edit
    o = next(o for o in session.state.gen.scene.objects if o.id == "fridge-0")
    page.mouse.click(*screen_xy(session, (o.x, o.y, -o.z)))
    wait_until(page, lambda: session.picking.controls is not None, "the gizmo on the picked fridge")
    settle(page)
    # the gizmo sits on the fridge's top; drag the arrow of the axis that separates fridge and counter
    # (browser x is the room's x, browser +z the room's -z)
    top = np.asarray(session.picking.controls.position)
    assert abs(top[1] - (o.y + o.size.y / 2)) < 0.1
    along_x = abs(counter.x - fridge.x) > abs(counter.z - fridge.z)
    axis = np.array((1.0, 0, 0)) if along_x else np.array((0, 0, 1.0))
    shift = counter.x - fridge.x if along_x else fridge.z - counter.z
    arrow = 0.5 * session.picking.controls.scale
    grab = screen_xy(session, top + arrow * axis)
    drop = screen_xy(session, top + (arrow + shift) * axis)
    page.mouse.move(*grab)
    page.mouse.down()
    page.mouse.move(*drop, steps=15)
    page.mouse.up()
    page.get_by_text(re.compile(r"fridge-0.* collides with")).first.wait_for(timeout=WAIT)
    moved = session.state.gen.layout.placement("fridge-0")
    if along_x:
        assert abs(moved.x - counter.x) < 0.3 and moved.z == fridge.z
    else:
        assert abs(moved.z - counter.z) < 0.3 and moved.x == fridge.x
    # the gizmo stays on it: the layout keeps 0.1 mm, and viser skips a position within its relative 1e-5 of the last
    assert session.picking.controls is not None and abs(session.picking.controls.position[2] + moved.z) < 1e-4

    page.get_by_role("tab", name="Scenes").click()
    page.get_by_role("button", name="Accept & save").click()
    page.get_by_text(re.compile(r"Save a scene that fails \d+ check")).wait_for(timeout=WAIT)
    page.get_by_role("button", name="Save anyway").click()
    saved = page.get_by_text(re.compile(r"Saved as scene \d+, version 1.*overriding"))
    saved.wait_for(timeout=WAIT)
    sid = int(re.search(r"scene (\d+)", saved.inner_text()).group(1))
    override = [e for e in studio.store.edits(sid) if e["kind"] == "override"]
    assert override and any("collides" in text for text in override[0]["before"])

    page.get_by_role("button", name="Undo").click()
    page.get_by_text(re.compile("Undid: move fridge-0")).wait_for(timeout=WAIT)
    restored = session.state.gen.layout.placement("fridge-0")
    assert (restored.x, restored.z, restored.rotation) == (fridge.x, fridge.z, fridge.rotation)
    assert session.state.findings == placed_findings
    # the undo is unsaved work: leaving the page asks first
    dialogs = []
    page.on("dialog", lambda d: (dialogs.append(d.type), d.dismiss()))
    page.evaluate("() => location.reload()")
    page.wait_for_timeout(500)
    assert dialogs == ["beforeunload"]


def test_typed_pose_onto_another_object_then_replace_the_rest_around_it(browser, studio):
    """The designer puts the fridge where the counter stands (typed pose), then presses Re-place the rest:
    the fridge stays where it was put, the others are placed around it without collisions; undo restores."""
    before = set(studio.sessions)
    page = open_studio(browser, studio)
    session = session_of(studio, before)
    generate(page, session, "Put a chilled bread on the counter", "kitchen")
    page.get_by_role("button", name="Re-place the rest").wait_for(state="hidden", timeout=WAIT)  # nothing picked
    counter = session.state.gen.layout.placement("countertop-0")
    o = next(o for o in session.state.gen.scene.objects if o.id == "fridge-0")
    page.mouse.click(*screen_xy(session, (o.x, o.y, -o.z)))
    wait_until(page, lambda: session.picking.selected == "fridge-0", "the picked fridge")
    page.get_by_role("button", name="Re-place the rest").click()  # nothing moved yet: it says what to do
    page.get_by_text(re.compile("Move an object first")).wait_for(timeout=WAIT)
    enter(page, "x (m)", round(counter.x, 2), session.picking.pose_x)
    enter(page, "z (m)", round(counter.z, 2), session.picking.pose_z)
    page.get_by_role("button", name="Apply pose").click()
    page.get_by_text(re.compile(r"fridge-0.* collides with")).first.wait_for(timeout=WAIT)
    put = session.state.gen.layout.placement("fridge-0")
    collided = session.state.gen

    page.get_by_role("button", name="Re-place the rest").click()
    page.get_by_text(re.compile(r"Re-placed around fridge-0")).wait_for(timeout=WAIT)
    now = session.state.gen.layout.placement("fridge-0")
    assert (now.x, now.z, now.rotation) == (put.x, put.z, put.rotation)
    wait_until(page, lambda: not any(f.kind == "collision" for f in session.state.findings), "no collision")
    assert not session.state.gen.layout.unplaced
    assert session.state.edits[-1].kind == "re-place" and session.state.edits[-1].target == "fridge-0"
    page.get_by_role("button", name="Undo").click()
    page.get_by_text(re.compile("Undid: re-place the rest")).wait_for(timeout=WAIT)
    assert session.state.gen is collided


def test_downloads_are_the_selected_version(browser, studio):
    before = set(studio.sessions)
    page = open_studio(browser, studio)
    session = session_of(studio, before)
    generate(page, session, "Put a chilled bread on the counter", "kitchen")
    page.get_by_role("tab", name="Scenes").click()
    enter(page, "Name", "versions", session.scenes.save_name)
    page.get_by_role("button", name="Accept & save").click()
    if session.state.findings:  # the placer's own layout may already fail a check (asked before saving)
        page.get_by_role("button", name="Save anyway").click()
    page.get_by_text(re.compile(r"Saved as scene \d+, version 1")).wait_for(timeout=WAIT)
    chair = session.state.gen.layout.placement("chair-1")
    settle(page)
    page.mouse.click(*object_xy(session, "chair-1", 0.9))  # a typed-in pose and a turn, in the picked panel
    wait_until(page, lambda: session.picking.selected == "chair-1", "chair-1 picked")
    enter(page, "x (m)", round(chair.x - 0.4, 2), session.picking.pose_x)
    page.get_by_role("button", name="Apply pose").click()
    page.get_by_text(re.compile(r"Moved `?chair-1`? .*typed pose")).wait_for(timeout=WAIT)
    page.get_by_role("button", name="+90°").click()
    page.get_by_text(re.compile(r"turn \+90")).wait_for(timeout=WAIT)
    page.get_by_role("button", name="Accept & save").click()
    if session.state.findings:
        page.get_by_role("button", name="Save anyway").click()
    saved = page.get_by_text(re.compile(r"Saved as scene \d+, version 2"))
    saved.wait_for(timeout=WAIT)
    sid = int(re.search(r"scene (\d+)", saved.inner_text()).group(1))
    assert field(page, "Version").input_value().startswith("v2")  # the dropdown follows the save

    choose(page, "Version", "v1: versions")
    with page.expect_download() as download:
        page.get_by_role("button", name="Download house JSON").click()
    assert download.value.suggested_filename == "versions-v1-house.json"
    house = json.loads(Path(download.value.path()).read_text())
    assert house == json.loads(json.dumps(to_house(studio.store.scene(sid, 1))))
    assert house != json.loads(json.dumps(to_house(studio.store.scene(sid, 2))))

    with page.expect_download() as download:
        page.get_by_role("button", name="Download GLB").click()
    assert download.value.suggested_filename == "versions-v1.glb"
    import trimesh

    glb = trimesh.load(io.BytesIO(Path(download.value.path()).read_bytes()), file_type="glb")
    furniture = [o.id for o in studio.store.scene(sid, 1).objects if family_of(o.type) != "block"]
    assert furniture and all(len(glb.geometry[i].faces) > 12 for i in furniture)


def test_generate_is_disabled_while_it_runs(browser, studio, monkeypatch):
    """Three quick clicks run one generation; the button is disabled and a progress line shows meanwhile.
    The pipeline is slowed down on purpose (a 1.5 s sleep) so that the clicks land while it runs."""
    before = set(studio.sessions)
    page = open_studio(browser, studio)
    session = session_of(studio, before)
    real = studio.pipeline.generate_from_graph

    def slow(*args, **kwargs):
        time.sleep(1.5)
        return real(*args, **kwargs)
    monkeypatch.setattr(studio.pipeline, "generate_from_graph", slow)
    button = page.get_by_role("button", name="Generate")
    button.click()
    page.get_by_text(re.compile("Planning the room and placing objects")).wait_for(timeout=WAIT)
    assert button.is_disabled()
    button.click(force=True)
    button.click(force=True)
    page.get_by_text(re.compile(r"Scene ready \(#1\)")).wait_for(timeout=WAIT)
    page.wait_for_timeout(2500)
    assert session.state.runs == 1 and button.is_enabled()
