"""What replaying the placer's steps as it made them (frontend/replay.py) costs the studio's step animation, in
chromium: one room with 29 steps and a solve from the start ("Turn on the lamp by the sofa", living room, seed 0),
played at 10 objects / s, alternating six times between the studio's `advance` and the one before the replay, which
dropped every object in at its final pose (the same view calls, without the step poses). Prints the time from Play
to the last step's caption and its ratio to the 0.1 s per step the speed asks for. Run from a tree's root:
PYTHONPATH=. python app/bench/results/studio-replay.py > app/bench/results/studio-replay.txt"""

import re
import statistics
import tempfile
import time

from app.bench.studio import ARGS
from app.pipeline import Pipeline
from frontend.server import Studio
from frontend.captions import step_caption
from frontend.placement_panel import PlacementPanel
from studio_db import Store

RUNS = 6


def final_poses(self: PlacementPanel) -> None:
    """The step animation before frontend/replay.py: each object dropped in where it stands now."""
    s = self.session
    if (next_step := self.next_step()) is None:
        return
    (step, shown), steps = next_step, s.state.steps
    obj = next((o for o in s.state.gen.scene.objects if o.id == step.object_id), None)
    self.step_md.content = step_caption(steps, shown, obj)
    if obj is None:
        return
    frames = max(2, min(8, int(20 / float(self.speed.value))))
    duration = min(0.25, 0.8 / float(self.speed.value))
    for k in range(1, frames + 1):
        s.view.settle(obj, k / frames)
        time.sleep(duration / frames)
    if shown == len(steps):
        s.view.heat_map(None)


def main() -> None:
    from playwright.sync_api import sync_playwright

    replay = PlacementPanel.advance
    times = {"replay (step poses)": [], "before (final poses)": []}
    with tempfile.TemporaryDirectory() as tmp:
        studio = Studio("127.0.0.1", 28090, Store(f"sqlite:///{tmp}/bench.db"), Pipeline())
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            page = browser.new_page(viewport={"width": 1400, "height": 900})
            page.goto(f"http://127.0.0.1:{studio.port}")
            page.get_by_role("button", name="Generate").wait_for(timeout=30_000)
            session = studio.sessions[max(studio.sessions)]
            session.instruction.value, session.room.value = "Turn on the lamp by the sofa", "living room"
            page.get_by_role("button", name="Generate").click()
            page.get_by_text(re.compile(r"Scene ready")).wait_for(timeout=60_000)
            page.get_by_role("tab", name="Placement").click()
            session.placement.speed.value = 10.0
            n = len(session.state.steps)
            for k in range(2 * RUNS):
                name = list(times)[k % 2]
                PlacementPanel.advance = replay if k % 2 == 0 else final_poses
                session.placement.step_md.content = ""  # the last play's caption is not the end of this one
                page.get_by_text(f"Step {n} / {n}").wait_for(state="detached", timeout=10_000)
                t0 = time.perf_counter()
                page.get_by_role("button", name="Play").click()
                page.get_by_text(f"Step {n} / {n}").wait_for(timeout=60_000)
                times[name].append(time.perf_counter() - t0)
                while session.state.playing:
                    time.sleep(0.05)
                page.wait_for_timeout(500)
            PlacementPanel.advance = replay
            browser.close()
        studio.stop()
    print(f"step animation of one room, {n} steps at 10 objects/s (ideal {n / 10:.1f} s), {RUNS} plays each, "
          "alternating")
    for name, runs in times.items():
        print(f"  {name:22s} median {statistics.median(runs):5.2f} s  (ratio to ideal "
              f"{statistics.median(runs) / (n / 10):.2f}; runs {', '.join(f'{t:.2f}' for t in runs)})")
    new, old = (statistics.median(r) for r in times.values())
    print(f"  replay / before        {new / old:.2f}")


if __name__ == "__main__":
    main()
