"""The Headset tab in a real browser: the designer reads the pairing token, the headset simulator (the
stand-in for the Quest app) pairs with it over the wire protocol, the designer presses "Send to headset"
and watches the progress and the glove feedback stream in."""

import asyncio
import importlib.util
import re
import threading
from pathlib import Path

import pytest
from studio_support import WAIT, field, launch, open_studio, start_studio

from app.bridge import bridge_for

playwright_api = pytest.importorskip("playwright.sync_api")
ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("headset_sim", ROOT / "unity-bridge" / "simulator" / "headset_sim.py")
sim_mod = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(sim_mod)


def test_send_to_headset_and_watch_feedback(tmp_path_factory, pipeline):
    from frontend.server import serve_api

    studio = start_studio(tmp_path_factory)
    api, port = serve_api(studio.store, studio.pipeline, "127.0.0.1", 21000)
    scene = pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0).scene
    studio.store.create_scene("bread for the headset", scene, 0, "dfs")
    bridge = bridge_for(studio.store)
    done = {}
    try:
        with playwright_api.sync_playwright() as p:
            browser = launch(p)
            page = open_studio(browser, studio)
            page.get_by_role("tab", name="Headset").click()
            token = bridge.token
            page.get_by_text(re.compile(f"Pairing token {token}")).wait_for(timeout=WAIT)

            async def headset():  # the stand-in headset, typing the token it read
                sim = sim_mod.HeadsetSimulator(f"ws://127.0.0.1:{port}/headset", token)
                await sim.connect()
                push = await asyncio.wait_for(sim.pushes.get(), 60)
                done["counts"] = await sim.run_scene(push, pace_s=0.05)
                done["acked"] = await sim.wait_acked(30)
                await sim.close()

            thread = threading.Thread(target=lambda: asyncio.run(headset()), daemon=True)
            thread.start()
            paired = field(page, "Paired headset")
            for _ in range(300):
                if paired.input_value().startswith("headset-1 · H3DS headset simulator"):
                    break
                page.wait_for_timeout(100)
            assert "connected" in paired.input_value()
            page.get_by_role("button", name="Send to headset").click()
            page.get_by_text(re.compile(r"Scene 1 v1 .*delivered")).wait_for(timeout=WAIT)
            thread.join(60)
            steps = done["counts"]["steps"]
            page.get_by_text(re.compile(rf"robot step {steps} of {steps}.*user accepted")).wait_for(timeout=WAIT)
            events = done["counts"]["glove_events"]
            page.get_by_text(f"{events} glove events stored").wait_for(timeout=WAIT)
            assert done["acked"] and bridge.feedback.count() == events
            assert page.get_by_text(re.compile(r"select.*Bread")).count() >= 1
            browser.close()
    finally:
        api.should_exit = True
        studio.stop()
