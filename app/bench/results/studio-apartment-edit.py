"""What editing one room of an apartment in the studio costs, in chromium, against generating the apartment again
(what a designer had to do before rooms of an apartment could be edited) and against the same edits of a single
room, in the same run.

For each of N tasks and seeds: an apartment (kitchen, living room, bedroom) and a single living room, each
generated (from the click on Generate to the status line), then edited in the living room: a constraint edit (its
first object's line becomes `middle`, typed into the Raw constraints field) from the click on Apply text to the line
saying it re-placed, and a typed pose (that object 0.3 m along x) from the click on Apply pose to the line saying it
moved. In-process, the same with the pipeline alone: `generate_apartment` (`generate`), the room's `replan` and its
`move`, each folded back into the apartment (`with_room`). Run from a tree's root:
PYTHONPATH=. python app/bench/results/studio-apartment-edit.py > app/bench/results/studio-apartment-edit.txt
"""

import re
import tempfile
import time

from app.bench.generate import quantile
from app.bench.studio import ARGS, studio_page
from app.pipeline import Pipeline, room_generation
from frontend.server import Studio
from models.language import RuleParser
from models.scene.apartment import with_room
from studio_db import Store

N = 8
ROOMS = ["kitchen", "living room", "bedroom"]
EDITED = 1  # the living room
TASKS = ("Put a chilled bread on the counter", "Turn on the lamp by the sofa", "Put the book on the bed",
         "Put a mug in the coffee machine")
SHIFT = 0.3  # m, the typed pose's move


def edited_text(plan) -> tuple[str, str]:
    """(the object edited, the room's constraint text with its line made `middle`)."""
    first = plan.objects[0].id
    return first, re.sub(rf"(?m)^{re.escape(first)} \|[^\n]*$", f"{first} | middle", plan.constraints)


def timed(make):
    t0 = time.perf_counter()
    out = make()
    return out, time.perf_counter() - t0


def in_process(pipeline: Pipeline, text: str, seed: int, house: bool) -> tuple[float, float, float]:
    """(generate, constraint edit, typed pose) in seconds: the apartment's living room (`house`) or a single room."""
    if house:
        apartment, generate = timed(lambda: pipeline.generate_apartment(text, ROOMS, seed))
        gen = room_generation(apartment, EDITED)
    else:
        gen, generate = timed(lambda: pipeline.generate(text, ROOMS[EDITED], seed))
    oid, constraints = edited_text(gen.plan)

    def back(new):
        return with_room(apartment, EDITED, new.plan, new.layout, seed) if house else new

    def move():
        p = gen.layout.placement(oid)
        return back(pipeline.move(gen, oid, p.x + SHIFT, p.z, p.rotation, seed))
    return generate, timed(lambda: back(pipeline.replan(gen, constraints, seed)))[1], timed(move)[1]


def wait_for(page, pattern: str) -> None:
    page.get_by_text(re.compile(pattern)).first.wait_for(timeout=120_000)


def in_browser(page, session, text: str, seed: int, house: bool) -> tuple[float, float, float]:
    """`in_process` in the studio's tab."""
    session.room.value = "apartment" if house else ROOMS[EDITED]
    session.instruction.value, session.seed.value = text, seed
    page.wait_for_timeout(300)
    run = session.state.runs + 1
    t0 = time.perf_counter()
    page.get_by_role("button", name="Generate").click()
    wait_for(page, rf"{'Apartment' if house else 'Scene'} ready \(#{run}\)|Error")
    generate = time.perf_counter() - t0
    oid, constraints = edited_text(session.apartment.current.plans[EDITED] if house else session.state.gen.plan)
    session.picking.pick(oid)  # in an apartment the living room becomes the one edited (as a click would; untimed)
    page.get_by_role("tab", name="Constraints").click()
    session.constraints.text.value = constraints
    session.constraints.message.content = ""  # the line the wait looks for, from the apartment before
    page.wait_for_timeout(300)
    plotted = session.placement.energy_plot.data
    t0 = time.perf_counter()
    page.get_by_role("button", name="Apply text").click()
    wait_for(page, "Re-placed after the edit|Error")
    replan = time.perf_counter() - t0
    for _ in range(300):  # the house's energy plot, drawn after the edit, is not timed with the move
        if session.placement.energy_plot.data is not plotted:
            break
        page.wait_for_timeout(100)
    session.picking.pick(oid)
    session.picking.pose_x.value = round(float(session.picking.pose_x.value) + SHIFT, 3)
    page.wait_for_timeout(300)
    t0 = time.perf_counter()
    page.get_by_role("button", name="Apply pose").click()
    wait_for(page, rf"Moved {re.escape(oid)} to|Error")
    move = time.perf_counter() - t0
    page.get_by_role("tab", name="Task").click()
    return generate, replan, move


def main() -> None:
    from playwright.sync_api import sync_playwright

    pipeline = Pipeline(parser=RuleParser())
    cases = [(TASKS[k % len(TASKS)], k) for k in range(N)]
    bare = {house: [in_process(pipeline, text, seed, house) for text, seed in cases] for house in (True, False)}
    with tempfile.TemporaryDirectory() as tmp:
        studio = Studio("127.0.0.1", 28090, Store(f"sqlite:///{tmp}/bench.db"), pipeline)
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            page = studio_page(browser, studio)
            session = studio.sessions[max(studio.sessions)]
            session.rooms.value = ", ".join(ROOMS)
            shown = {True: [], False: []}
            for text, seed in cases:  # an apartment, then the single room, per task
                for house in (True, False):
                    shown[house].append(in_browser(page, session, text, seed, house))
            browser.close()
        studio.stop()
    print(f"{N} tasks, each as an apartment ({', '.join(ROOMS)}) and as a single {ROOMS[EDITED]}, the {ROOMS[EDITED]} "
          "edited (rule parser, plan2place); p50 (p90) ms")
    for label, runs in (("apartment, in chromium", shown[True]), ("single room, in chromium", shown[False]),
                        ("apartment, pipeline alone", bare[True]), ("single room, pipeline alone", bare[False])):
        gen, replan, move = ([r[i] for r in runs] for i in range(3))
        print(f"  {label:27s} Generate {1000 * quantile(gen, .5):6.0f} ({1000 * quantile(gen, .9):6.0f})   "
              f"constraint edit {1000 * quantile(replan, .5):5.0f} ({1000 * quantile(replan, .9):5.0f}), "
              f"{quantile(replan, .5) / quantile(gen, .5):.2f} x Generate   "
              f"typed pose {1000 * quantile(move, .5):5.0f} ({1000 * quantile(move, .9):5.0f}), "
              f"{quantile(move, .5) / quantile(gen, .5):.2f} x Generate")


if __name__ == "__main__":
    main()
