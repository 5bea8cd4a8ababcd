"""Shared helpers for the studio's browser tests: the studio, chromium, viser's inputs, and real mouse
events at an object's projected screen position (computed from the tab's camera, as three.js does)."""

from __future__ import annotations

import random
import re
import time
from pathlib import Path

import numpy as np
import pytest

from frontend import camera
from frontend.view import world

CHROMIUM = "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]
SCREENSHOTS = Path(__file__).resolve().parent.parent / "out" / "screenshots"
WAIT = 30_000
VIEWPORT = {"width": 1400, "height": 900}


def start_studio(tmp_path_factory):
    from frontend.server import Studio
    from studio_db import Store

    store = Store(f"sqlite:///{tmp_path_factory.mktemp('db') / 'studio.db'}")
    return Studio("127.0.0.1", random.randint(20000, 40000), store)


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    """A studio on a fresh SQLite database, one per test module."""
    s = start_studio(tmp_path_factory)
    yield s
    s.stop()


@pytest.fixture(scope="module")
def browser():
    """Debian's chromium, one per test module."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        b = launch(p)
        yield b
        b.close()


def launch(playwright_api):
    assert Path(CHROMIUM).exists(), "Debian's chromium is missing: `make test` installs it (apt-get install chromium)"
    return playwright_api.chromium.launch(executable_path=CHROMIUM, args=ARGS)


def field(page, label: str):
    """A viser input: the input or textarea in the row (the label's ancestor flex div) of its label."""
    row = page.locator(f"xpath=//label[normalize-space(text())='{label}']"
                       "/ancestor::div[contains(@class, 'mantine-Flex-root')][1]").first
    row.wait_for(timeout=WAIT)
    return row.locator("input, textarea").first


def choose(page, label: str, option: str, handle=None):
    """Pick a dropdown option; with the server's `handle`, wait until the server holds it (see `enter`)."""
    field(page, label).click()
    page.get_by_role("option", name=option).first.click()
    if handle is not None:
        wait_until(page, lambda: handle.value == option, f"{label} = {option!r} on the server")


def enter(page, label: str, value, handle):
    """Type `value` into an input and wait until the server's `handle` holds it. viser's client sends every
    input's updates through one 50 ms throttle that keeps only the latest message, so an input changed
    within 50 ms of another would lose its update (seen in CI: the rooms typed right after the room type)."""
    field(page, label).fill(str(value))
    wait_until(page, lambda: handle.value == value, f"{label} = {value!r} on the server")


_OPENED: list = []  # the browser contexts `open_studio` made, closed after each test by `close_tabs`


def open_studio(browser, studio):
    context = browser.new_context(viewport=VIEWPORT)
    _OPENED.append(context)
    page = context.new_page()
    page.goto(f"http://127.0.0.1:{studio.port}")
    page.get_by_role("button", name="Generate").wait_for(timeout=WAIT)
    return page


@pytest.fixture(autouse=True)
def close_tabs():
    """A test's studio tabs are closed after it. An open tab keeps drawing the 3D view in software (chromium runs
    without a GPU), and the tabs left by earlier tests of a module slowed its later ones past their waits (seen on
    a 2-core machine slower per core: 17 s for a test alone, 110 s as the fourth)."""
    yield
    while _OPENED:
        context = _OPENED.pop()
        if context.browser is not None and context.browser.is_connected():
            context.close()


def session_of(studio, before: set[int]):
    """The session of the tab that connected after `before` (the ids of the sessions there were). The studio
    registers a session once its panel is built, and the tab may draw the panel's first buttons before that
    (seen in CI): wait for it."""
    for _ in range(WAIT // 100):
        new = [sid for sid in list(studio.sessions) if sid not in before]
        if new:
            assert len(new) == 1, f"{len(new)} new sessions"
            return studio.sessions[new[0]]
        time.sleep(0.1)
    pytest.fail("the tab's session never registered")


def generate(page, session, instruction: str, room: str, run: int | None = None):
    """Type and choose, each waiting until the tab's `session` holds it (see `enter`), then Generate."""
    enter(page, "Instruction", instruction, session.instruction)
    choose(page, "Room type", room, session.room)
    page.get_by_role("button", name="Generate").click()
    page.get_by_text(re.compile(rf"Scene ready \(#{run}\)" if run else "Scene ready")).wait_for(timeout=WAIT)
    dismiss_notices(page)


def dismiss_notices(page):
    """Close viser's notices (the "software WebGL" one, as chromium runs without a GPU): one covers the view's top
    left corner and takes the mouse events meant for the scene there."""
    close = page.locator(".mantine-Notification-root button")
    for i in reversed(range(close.count())):
        close.nth(i).click()


def settle(page, frames: int = 3):
    """Let the browser apply queued messages and draw a few frames."""
    page.wait_for_timeout(300)
    page.evaluate("n => new Promise(r => { const f = () => --n ? requestAnimationFrame(f) : r(); "
                  "requestAnimationFrame(f); })", frames)


def screen_xy(session, point) -> tuple[float, float]:
    """Position in the page (CSS pixels, as mouse events take it) of a point in the browser's frame, seen by the
    tab's camera. Not the camera's drawing-buffer pixels: viser lowers its resolution while frames are slow (seen
    under load: a 1400 x 900 page drawn at 1225 x 787), and a HiDPI screen doubles it."""
    cam = session.client.camera
    look = np.asarray(cam.look_at) - np.asarray(cam.position)
    x, y = camera.project([point], cam.position, look, cam.fov, *session.canvas())[0]
    return float(x), float(y)


def object_xy(session, object_id: str, height: float = 0.5) -> tuple[float, float]:
    """Screen position of a point `height` of the way up the object's centre line."""
    o = next(o for o in session.state.gen.scene.all_objects() if o.id == object_id)
    return screen_xy(session, world(o.x, o.y - o.size.y / 2 + height * o.size.y, o.z))


def wait_until(page, condition, what: str, timeout_ms: int = WAIT):
    """Poll a server-side condition while the browser keeps running."""
    for _ in range(timeout_ms // 100):
        if condition():
            return
        page.wait_for_timeout(100)
    pytest.fail(f"timed out waiting for {what}")
