"""Where a Generate's wait in the studio goes (chromium, software WebGL): from the click to the server's handler, the
handler until it queues "Scene ready" (parse, pipeline, drawing the scene's messages, panels), and from then until
the browser shows that line (the browser taking in and drawing what was sent before it). Run from a tree's root:
PYTHONPATH=. python app/bench/results/studio-latency.py 20 > app/bench/results/studio-latency.txt"""
import re, sys, tempfile, time, statistics
from app.bench.generate import pick_instructions
from app.bench.studio import ARGS, fill_in, studio_page
from app.pipeline import Pipeline
from models.language import RuleParser
from playwright.sync_api import sync_playwright
from frontend.server import Studio
from studio_db import Store
n = int(sys.argv[1])
from frontend import session as S
T = {}
orig_gen = S.StudioSession.generate
def gen(self):
    T["enter"] = time.perf_counter(); orig_gen(self); T["exit"] = time.perf_counter()
S.StudioSession.generate = gen
orig_say = S.StudioSession.say
def say(self, text):
    if text.startswith("Scene ready"): T["say"] = time.perf_counter()
    return orig_say(self, text)
S.StudioSession.say = say
items = pick_instructions(n)
pipeline = Pipeline(parser=RuleParser())
with tempfile.TemporaryDirectory() as tmp:
    studio = Studio("127.0.0.1", 28090, Store(f"sqlite:///{tmp}/b.db"), pipeline)
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
        page = studio_page(browser, studio)
        rows, parts = [], []
        for i, (text, room) in enumerate(items):
            fill_in(page, text, room, i + 1)
            t0 = time.perf_counter()
            page.get_by_role("button", name="Generate").click()
            loc = page.get_by_text(re.compile(rf"Scene ready \(#{i + 1}\)"))
            loc.wait_for(timeout=60_000)
            wait = time.perf_counter() - t0
            server = float(re.search(r"\((\d+) ms\)", loc.inner_text()).group(1)) / 1000
            rows.append((wait, server))
            parts.append((T["enter"] - t0, T["say"] - T["enter"], t0 + wait - T["say"]))
        med = lambda xs: 1000 * statistics.median(xs)
        print(f"{n} Generates (rule parser, plan2place), p50 ms: click -> scene ready {med(r[0] for r in rows):.0f}; "
              f"click -> handler {med(p[0] for p in parts):.0f}, handler -> status queued {med(p[1] for p in parts):.0f} "
              f"(of it the pipeline step, drawing and panels {med(r[1] for r in rows):.0f}), queued -> shown {med(p[2] for p in parts):.0f}")
        browser.close()
