"""Studio speed in a real browser (Debian's chromium via Playwright): what a designer waits for.

- Generate -> first complete 3D scene: from the click to the status line saying the scene is ready
  (sent after every object of the scene has been pushed to the browser), over N instructions.
- Step animation: playing all steps at 10 objects / s against the 0.1 s per object it should take.
- Memory: resident set of this process (studio + pipeline) before the studio starts and with one
  scene open (the browser is a separate process and not counted).
The in-process baseline is the pipeline alone (no browser), timed on the same instructions.
"""

from __future__ import annotations

import re
import statistics
import tempfile
import time
from pathlib import Path

from app.bench.generate import pick_instructions, quantile
from app.pipeline import Pipeline

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


def main(args) -> int:
    from playwright.sync_api import sync_playwright

    from frontend.server import Studio
    from studio_db import Store

    items = pick_instructions(args.n)
    base_rss = rss_mb()
    pipeline = Pipeline()
    bare = []
    for i, (text, room) in enumerate(items):
        t0 = time.perf_counter()
        pipeline.generate(text, room, seed=i)
        bare.append(time.perf_counter() - t0)
    with tempfile.TemporaryDirectory() as tmp:
        studio = Studio("127.0.0.1", 28080, Store(f"sqlite:///{tmp}/bench.db"), pipeline)
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            page = browser.new_page(viewport={"width": 1400, "height": 900})
            page.goto(f"http://127.0.0.1:{studio.port}")
            page.get_by_role("button", name="Generate").wait_for(timeout=30_000)
            waits = []
            for i, (text, room) in enumerate(items):
                _field(page, "Instruction").fill(text)
                _field(page, "Seed").fill(str(i + 1))
                _field(page, "Room type").click()
                page.get_by_role("option", name=room).first.click()
                t0 = time.perf_counter()
                page.get_by_role("button", name="Generate").click()
                page.get_by_text(re.compile(rf"Scene ready \(#{i + 1}\)|Error")).wait_for(timeout=60_000)
                waits.append(time.perf_counter() - t0)
            one_scene_rss = rss_mb()
            page.get_by_role("tab", name="Placement").click()
            session = next(iter(studio.sessions.values()))
            session.speed.value = 10.0  # the slider's handle, as a drag would set it
            n_steps = len(session.state.steps)
            t0 = time.perf_counter()
            page.get_by_role("button", name="Play").click()
            page.get_by_text(f"Step {n_steps} / {n_steps}").wait_for(timeout=60_000)
            played = time.perf_counter() - t0
            browser.close()
        studio.stop()
    print(f"studio in chromium, {len(waits)} ALFRED valid_unseen instructions (rule parser, dfs)")
    print(f"  Generate -> scene ready    p50 {1000 * quantile(waits, .5):7.0f} ms   p90 {1000 * quantile(waits, .9):7.0f} ms")
    print(f"  pipeline alone (baseline)  p50 {1000 * quantile(bare, .5):7.0f} ms   -> browser round trip adds "
          f"{1000 * (quantile(waits, .5) - quantile(bare, .5)):.0f} ms")
    print(f"  step animation             {n_steps} steps at 10 objects/s in {played:.2f} s "
          f"(ideal {n_steps / 10:.2f} s, ratio {played / max(n_steps / 10, 1e-9):.2f})")
    print(f"  memory (RSS)               {base_rss:.0f} MB before, {one_scene_rss:.0f} MB with the studio and "
          f"one scene open (+{one_scene_rss - base_rss:.0f} MB)")
    print(f"  mean wait                  {1000 * statistics.mean(waits):.0f} ms")
    return 0
