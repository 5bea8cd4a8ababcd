"""The studio in a real browser (Debian's chromium driven by Playwright)."""

import json
import random
import re
from pathlib import Path

import pytest

from frontend.server import Studio
from studio_db import Store

playwright_api = pytest.importorskip("playwright.sync_api")
CHROMIUM = "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]
SCREENSHOTS = Path(__file__).resolve().parent.parent / "out" / "screenshots"
WAIT = 30_000


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    store = Store(f"sqlite:///{tmp_path_factory.mktemp('db') / 'studio.db'}")
    s = Studio("127.0.0.1", random.randint(20000, 40000), store)
    yield s
    s.stop()


@pytest.fixture(scope="module")
def browser():
    assert Path(CHROMIUM).exists(), "Debian's chromium is missing: `make test` installs it (apt-get install chromium)"
    with playwright_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        yield b
        b.close()


def field(page, label: str):
    """A viser input: the input or textarea in the row (the label's ancestor flex div) of its label."""
    row = page.locator(f"xpath=//label[normalize-space(text())='{label}']"
                       "/ancestor::div[contains(@class, 'mantine-Flex-root')][1]").first
    row.wait_for(timeout=WAIT)
    return row.locator("input, textarea").first


def choose(page, label: str, option: str):
    field(page, label).click()
    page.get_by_role("option", name=option).first.click()


def open_studio(browser, studio):
    page = browser.new_context(viewport={"width": 1400, "height": 900}).new_page()
    page.goto(f"http://127.0.0.1:{studio.port}")
    page.get_by_role("button", name="Generate").wait_for(timeout=WAIT)
    return page


def generate(page, instruction: str, room: str):
    field(page, "Instruction").fill(instruction)
    choose(page, "Room type", room)
    page.get_by_role("button", name="Generate").click()
    page.get_by_text(re.compile("Scene ready")).wait_for(timeout=WAIT)


def test_designer_flow(browser, studio):
    page = open_studio(browser, studio)
    generate(page, "Put a chilled bread on the counter", "kitchen")
    graph = page.get_by_text("Key objects:").locator("xpath=..")
    assert "Bread" in graph.inner_text()
    assert "Fridge" in page.get_by_text("Inference objects:").locator("xpath=..").inner_text()
    assert "CounterTop" in page.get_by_text("Anchor object:").locator("xpath=..").inner_text()

    # picking and dragging act on the 3D canvas; the test drives the same handles a click and a drag do
    session = next(iter(studio.sessions.values()))
    page.get_by_role("tab", name="Constraints").click()
    session.pick("fridge-0")
    page.get_by_text(re.compile(r"fridge-0.*\(Fridge, inference\)")).wait_for(timeout=WAIT)
    session.controls.position = (0.6, 0.02, -0.6)
    session.dragged("fridge-0")
    page.get_by_text(re.compile("Moved `?fridge-0`? to")).wait_for(timeout=WAIT)
    assert session.state.edits[-1].kind == "move"

    page.get_by_role("tab", name="Placement").click()
    page.get_by_role("button", name="Step").click()
    page.get_by_text(re.compile(r"Step 1 / \d+")).wait_for(timeout=WAIT)
    page.get_by_role("button", name="Step").click()
    page.get_by_text(re.compile(r"Step 2 / \d+")).wait_for(timeout=WAIT)

    page.get_by_role("tab", name="Constraints").click()
    raw = field(page, "Raw constraints")
    original = raw.input_value()
    raw.fill(original + "\nghost-line | levitate")
    page.get_by_role("button", name="Apply text").click()
    page.get_by_text(re.compile("Edit not applied")).wait_for(timeout=WAIT)
    edited = re.sub(r"fridge-0 \| edge[^\n]*", "fridge-0 | middle | far, countertop-0", original)
    raw.fill(edited)
    page.get_by_role("button", name="Apply text").click()
    moved = page.get_by_text(re.compile("Re-placed after the edit"))
    moved.wait_for(timeout=WAIT)
    assert "fridge-0" in moved.inner_text()

    page.get_by_role("tab", name="Scenes").click()
    field(page, "Name").fill("bread in the browser")
    page.get_by_role("button", name="Accept & save").click()
    saved = page.get_by_text(re.compile(r"Saved as scene \d+, version 1"))
    saved.wait_for(timeout=WAIT)
    scene_id = re.search(r"scene (\d+)", saved.inner_text()).group(1)
    assert [e["kind"] for e in studio.store.edits(int(scene_id))] == ["move", "constraints"]
    with page.expect_download() as download:
        page.get_by_role("button", name="Download house JSON").click()
    house = json.loads(Path(download.value.path()).read_text())
    assert house["metadata"]["schema"] == "1.0.0" and download.value.suggested_filename == "house.json"
    with page.expect_download() as download:
        page.get_by_role("button", name="Download GLB").click()
    assert Path(download.value.path()).read_bytes()[:4] == b"glTF"
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SCREENSHOTS / "studio.png"))

    page.reload()
    page.get_by_role("button", name="Generate").wait_for(timeout=WAIT)
    page.get_by_role("tab", name="Scenes").click()
    choose(page, "Stored scene", f"{scene_id}: bread in the browser")
    page.get_by_role("button", name="Open").click()
    page.get_by_text(re.compile(rf"Opened scene {scene_id}, version 1")).wait_for(timeout=WAIT)


def test_two_designers_do_not_see_each_other(browser, studio):
    a, b = open_studio(browser, studio), open_studio(browser, studio)
    generate(a, "Put a chilled bread on the counter", "kitchen")
    generate(b, "Look at the book under the desk lamp", "bedroom")
    assert "Bread" in a.get_by_text("Key objects:").locator("xpath=..").inner_text()
    assert "Book" in b.get_by_text("Key objects:").locator("xpath=..").inner_text()
    assert "Book" not in a.get_by_text("Key objects:").locator("xpath=..").inner_text()
    assert "kitchen" in a.get_by_text(re.compile("Scene ready")).inner_text()
    assert "bedroom" in b.get_by_text(re.compile("Scene ready")).inner_text()
