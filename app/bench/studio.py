"""Studio speed in a real browser (Debian's chromium via Playwright): what a designer waits for.

- First render in a fresh tab: a new tab, one Generate, until the status line says the scene is ready
  and until every object node is in the browser's scene tree and two more frames are drawn; with what
  was sent for it (messages by kind, bytes, labels). Fresh tabs alternate between the studio's view
  setup and viser's default lighting (the "city" environment map and shadow-casting default lights, the
  setup before issue 11), the baseline, in the same run.
- Generate -> first complete 3D scene: from the click to the status line saying the scene is ready
  (sent after every object of the scene has been pushed to the browser), over N instructions.
- Step animation: playing all steps at 10 objects / s against the 0.1 s per object it should take.
- Re-place the rest: after each Generate the third object of the placing order is put onto the first's
  pose (the designer's move, made server-side and not timed), then from the click on "Re-place the rest" to
  the status line saying so; against Generate on the same scenes (and in-process: `replace_around` against
  placing the whole plan again).
- Memory: resident set of this process (studio + pipeline) before the studio starts and with one
  scene open (the browser is a separate process and not counted).
The in-process baseline is the pipeline alone (no browser), timed on the same instructions.
"""

from __future__ import annotations

import collections
import re
import statistics
import tempfile
import time
from pathlib import Path

import msgspec

from app.bench.generate import pick_instructions, quantile
from app.pipeline import Pipeline
from models.language import RuleParser
from models.placement import DEFAULT_SOLVER, PlacementProblem

ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def rss_mb() -> float:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def _field(page, label: str):
    return page.locator(f"xpath=//label[normalize-space(text())='{label}']"
                        "/ancestor::div[contains(@class, 'mantine-Flex-root')][1]").first.locator("input, textarea").first


def studio_page(browser, studio):
    """A tab of `studio`, once its Generate button is there."""
    page = browser.new_page(viewport={"width": 1400, "height": 900})
    page.goto(f"http://127.0.0.1:{studio.port}")
    page.get_by_role("button", name="Generate").wait_for(timeout=30_000)
    return page


def fill_in(page, text: str, room: str, seed: int) -> None:
    """The designer types the instruction and the seed and picks the room type (Generate not yet clicked)."""
    _field(page, "Instruction").fill(text)
    _field(page, "Seed").fill(str(seed))
    _field(page, "Room type").click()
    page.get_by_role("option", name=room).first.click()


FRESH_TABS = 3  # per variant
WATCH_JS = """n => {
  const t = window.__firstRender = {t0: performance.now()};
  const count = () => Object.keys(window.__viserSceneTree.getState())
    .filter(k => /^\\/objects\\/[^/]+$/.test(k)).length;
  const frame = () => {
    if (t.nodes === undefined && count() >= n) t.nodes = performance.now();
    else if (t.nodes !== undefined) { t.drawn = performance.now(); return; }
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
}"""


def _count_messages(session) -> list:
    """Record every message queued for this tab: (kind, bytes)."""
    sent = []
    conn = session.client._websock_connection
    queue = conn.queue_message

    def counting(message):
        sent.append((type(message).__name__, len(msgspec.msgpack.encode(message.as_serializable_dict()))))
        return queue(message)
    conn.queue_message = counting
    return sent


def first_render(browser, studio, baseline: bool, n_objects: int) -> dict:
    """One fresh tab, one Generate of the studio's default task (`n_objects` objects): seconds to the status line
    and to the drawn scene, and what was sent."""
    page = browser.new_page(viewport={"width": 1400, "height": 900})
    before = set(studio.sessions)
    page.goto(f"http://127.0.0.1:{studio.port}")
    page.get_by_role("button", name="Generate").wait_for(timeout=30_000)
    session = next(s for sid, s in studio.sessions.items() if sid not in before)
    if baseline:  # viser's defaults, as the studio had them before issue 11
        session.client.scene.configure_environment_map("city")
        session.client.scene.configure_default_lights(True, cast_shadow=True)
    page.wait_for_timeout(500)
    sent = _count_messages(session)
    page.evaluate(WATCH_JS, n_objects)
    t0 = time.perf_counter()
    page.get_by_role("button", name="Generate").click()
    page.get_by_text(re.compile("Scene ready")).wait_for(timeout=60_000)
    ready = time.perf_counter() - t0
    page.wait_for_function("() => window.__firstRender.drawn !== undefined", timeout=60_000)
    marks = page.evaluate("() => window.__firstRender")
    drawn = (marks["drawn"] - marks["t0"]) / 1000  # the first frame drawn with every object in it
    assert len(session.state.gen.scene.all_objects()) == n_objects
    page.close()
    return {"ready": ready, "drawn": drawn, "sent": list(sent), "objects": n_objects}


def dragged(gen) -> str:
    """The object a bench's designer moves: the third of the placing order (the first two if fewer)."""
    order = PlacementProblem.from_plan(gen.plan).order
    return order[min(2, len(order) - 1)].id


def designer_move(pipeline: Pipeline, gen):
    """`gen` with its `dragged` object put onto the first object's pose (a drag into a collision)."""
    onto = gen.layout.placement(PlacementProblem.from_plan(gen.plan).order[0].id)
    return pipeline.move(gen, dragged(gen), onto.x, onto.z, onto.rotation)


def main(args) -> int:
    from playwright.sync_api import sync_playwright

    from frontend.server import Studio
    from frontend.session import DEFAULT_INSTRUCTION
    from studio_db import Store

    items = pick_instructions(args.n)
    base_rss = rss_mb()
    pipeline = Pipeline(parser=RuleParser())  # the rules, as the figures in the README
    bare, bare_place, bare_around = [], [], []
    for i, (text, room) in enumerate(items):
        t0 = time.perf_counter()
        gen = pipeline.generate(text, room, seed=i)
        bare.append(time.perf_counter() - t0)
        moved = designer_move(pipeline, gen)
        t0 = time.perf_counter()
        pipeline.place(moved.plan, seed=i)
        bare_place.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        pipeline.replace_around(moved, [dragged(moved)], seed=i)
        bare_around.append(time.perf_counter() - t0)
    n_default = len(pipeline.generate(DEFAULT_INSTRUCTION, "kitchen", seed=0).scene.all_objects())  # a tab's first
    with tempfile.TemporaryDirectory() as tmp:
        studio = Studio("127.0.0.1", 28080, Store(f"sqlite:///{tmp}/bench.db"), pipeline)
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            fresh = {False: [], True: []}
            for k in range(2 * FRESH_TABS):
                baseline = bool(k % 2)
                fresh[baseline].append(first_render(browser, studio, baseline, n_default))
            page = studio_page(browser, studio)
            waits, around = [], []
            for i, (text, room) in enumerate(items):
                fill_in(page, text, room, i + 1)
                t0 = time.perf_counter()
                page.get_by_role("button", name="Generate").click()
                page.get_by_text(re.compile(rf"Scene ready \(#{2 * i + 1}\)|Error")).wait_for(timeout=60_000)
                waits.append(time.perf_counter() - t0)
                session = studio.sessions[max(studio.sessions)]
                moved = designer_move(pipeline, session.state.gen)
                name = dragged(moved)
                onto = moved.layout.placement(name)
                session.picking.move_to(name, onto.x, onto.z, onto.rotation, how="bench")
                session.picking.pick(name)
                button = page.get_by_role("button", name="Re-place the rest")
                button.wait_for(state="visible", timeout=30_000)
                page.wait_for_timeout(300)  # the picked object's panel has opened and the move's checks are shown
                t0 = time.perf_counter()
                button.click()
                page.get_by_text(re.compile(rf"Re-placed around {name}|Error")).wait_for(timeout=60_000)
                around.append(time.perf_counter() - t0)
            one_scene_rss = rss_mb()
            page.get_by_role("tab", name="Placement").click()
            session = studio.sessions[max(studio.sessions)]
            session.placement.speed.value = 10.0  # the slider's handle, as a drag would set it
            n_steps = len(session.state.steps)
            t0 = time.perf_counter()
            page.get_by_role("button", name="Play").click()
            page.get_by_text(f"Step {n_steps} / {n_steps}").wait_for(timeout=60_000)
            played = time.perf_counter() - t0
            browser.close()
        studio.stop()
    print(f"first render in a fresh tab (chromium, software WebGL), {FRESH_TABS} tabs per variant, one Generate each")
    for baseline, label in ((True, "viser default lighting (baseline)"), (False, "studio view setup")):
        runs = fresh[baseline]
        print(f"  {label:34s} status line {statistics.median(r['ready'] for r in runs):5.2f} s   "
              f"scene drawn {statistics.median(r['drawn'] for r in runs):5.2f} s (median)")
    ratio = statistics.median(r["drawn"] for r in fresh[True]) / statistics.median(r["drawn"] for r in fresh[False])
    print(f"  baseline / studio (scene drawn)    {ratio:.1f}x")
    sent = fresh[False][0]["sent"]
    kinds = collections.Counter(kind for kind, _ in sent)
    print(f"  sent for one Generate: {len(sent)} messages, {sum(b for _, b in sent) / 1024:.0f} KiB, "
          f"{kinds.get('LabelMessage', 0)} labels for {fresh[False][0]['objects']} objects; by kind: "
          + ", ".join(f"{k.removesuffix('Message')} {n}" for k, n in kinds.most_common(8)))
    print(f"studio in chromium, {len(waits)} ALFRED valid_unseen instructions (rule parser, {DEFAULT_SOLVER})")
    print(f"  Generate -> scene ready    p50 {1000 * quantile(waits, .5):7.0f} ms   p90 {1000 * quantile(waits, .9):7.0f} ms")
    print(f"  pipeline alone (baseline)  p50 {1000 * quantile(bare, .5):7.0f} ms   -> browser round trip adds "
          f"{1000 * (quantile(waits, .5) - quantile(bare, .5)):.0f} ms")
    print(f"  Re-place the rest -> ready p50 {1000 * quantile(around, .5):7.0f} ms   p90 {1000 * quantile(around, .9):7.0f} ms"
          f"   ({quantile(around, .5) / quantile(waits, .5):.2f} x Generate's p50)")
    print(f"  in-process: replace_around p50 {1000 * quantile(bare_around, .5):.0f} ms, placing the whole plan again "
          f"p50 {1000 * quantile(bare_place, .5):.0f} ms (ratio {quantile(bare_around, .5) / quantile(bare_place, .5):.2f})")
    print(f"  step animation             {n_steps} steps at 10 objects/s in {played:.2f} s "
          f"(ideal {n_steps / 10:.2f} s, ratio {played / max(n_steps / 10, 1e-9):.2f})")
    print(f"  memory (RSS)               {base_rss:.0f} MB before, {one_scene_rss:.0f} MB with the studio and "
          f"one scene open (+{one_scene_rss - base_rss:.0f} MB)")
    print(f"  mean wait                  {1000 * statistics.mean(waits):.0f} ms")
    return 0
