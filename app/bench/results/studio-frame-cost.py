"""Where the studio's wait after an edit goes when the browser draws without a GPU (headless chromium, SwiftShader).

viser's client (frameloop "demand") applies a message that touches the 3D scene (a moved object, a snippet of
JavaScript) in the next frame it draws; only messages for the panel alone are applied at once. So after a typed
pose, the status line that follows the moved object shows once a frame of the room has been drawn. This times, per
page size and pixel ratio, a scene message followed by a status line, from the server's call to the line on the
page: with no scene, and with a kitchen on screen. The pixel ratio is viser's own adaptive one (it settles at 0.75
of the screen's when frames are slow) or fixed by the URL's `?fixedDpr=`. Run from a tree's root:
PYTHONPATH=. python app/bench/results/studio-frame-cost.py > app/bench/results/studio-frame-cost.txt
"""

import re
import statistics
import tempfile
import time

from app.bench.studio import ARGS, fill_in
from app.pipeline import Pipeline
from frontend.server import Studio
from models.language import RuleParser
from studio_db import Store

PAGES = ((1400, 900, ""), (1400, 900, "?fixedDpr=0.75"), (1400, 900, "?fixedDpr=0.5"), (700, 450, ""))
TRIES = 8


def scene_then_status(page, session, tag: str) -> float:
    """ms from queuing a scene message and a status line to the line on the page."""
    t0 = time.perf_counter()
    session._run_js(f"window.__frameProbe = '{tag}';")  # a scene-side message: applied with the next frame
    session.say(f"Status {tag}")
    page.get_by_text(tag).wait_for(timeout=60_000)
    return 1000 * (time.perf_counter() - t0)


def p50(page, session, label: str) -> float:
    times = []
    for k in range(TRIES):
        times.append(scene_then_status(page, session, f"probe{label}{k}"))
        page.wait_for_timeout(300)
    return statistics.median(times)


def main() -> None:
    from playwright.sync_api import sync_playwright

    with tempfile.TemporaryDirectory() as tmp:
        studio = Studio("127.0.0.1", 28090, Store(f"sqlite:///{tmp}/bench.db"), Pipeline(parser=RuleParser()))
        print(f"p50 of {TRIES} ms, a scene message then a status line, server call -> line shown (headless chromium, "
              "SwiftShader)")
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            for width, height, query in PAGES:
                page = browser.new_page(viewport={"width": width, "height": height})
                page.goto(f"http://127.0.0.1:{studio.port}/{query}")
                page.get_by_role("button", name="Generate").wait_for(timeout=60_000)
                page.wait_for_timeout(2000)
                session = studio.sessions[max(studio.sessions)]
                empty = p50(page, session, "empty")
                fill_in(page, "Put a chilled bread on the counter", "kitchen", 1)
                page.get_by_role("button", name="Generate").click()
                page.get_by_text(re.compile(r"Scene ready")).first.wait_for(timeout=60_000)
                page.wait_for_timeout(3000)  # viser's adaptive pixel ratio settles
                kitchen = p50(page, session, "kitchen")
                ratio = page.evaluate("() => Math.max(...[...document.querySelectorAll('canvas')].map(c => "
                                      "c.width / Math.max(1, c.getBoundingClientRect().width)))")
                print(f"  {width}x{height} {query or '(adaptive)':16s} pixel ratio {ratio:.2f}: "
                      f"no scene {empty:4.0f}, kitchen {kitchen:4.0f}")
                page.close()
            browser.close()
        studio.stop()


if __name__ == "__main__":
    main()
