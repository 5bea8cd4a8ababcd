"""What an edit through the HTTP API (POST /edit) costs against generating the scene again (POST /generate, what a
script had to do before /edit existed), in the same process and run.

For each of N tasks and seeds, a single room (the task's own) and an apartment (kitchen, living room, bedroom; the
living room edited) are generated through the API, then edited three times, each from the generated value: a move
(the room's first object 0.3 m along x), a constraint edit (that object's line made `middle`) and a re-place around
the moved object (move and replace_around in one request). In an apartment, a move in each of two rooms (the living
room's and the kitchen's first objects) is made in one request (each edit naming its room) and as two requests, the
second sent the first's answer, as a script without per-edit rooms had to. Each request is timed from the client's
call to its parsed answer (FastAPI's TestClient: the JSON body in and out, validation, the pipeline); `apply_edits`
alone, on the same values, gives the pipeline's share. Run from a tree's root:
PYTHONPATH=. python app/bench/results/api-edit.py > app/bench/results/api-edit.txt
"""

import json
import re
import tempfile
import time

from fastapi.testclient import TestClient

from app.api import create_app
from app.bench.generate import quantile
from app.editing import Constraints, Move, ReplaceAround, apply_edits, room_of
from app.pipeline import Pipeline
from models.language import RuleParser
from models.values import Scene
from models.values.apartment import Apartment
from studio_db import Store

N = 12
ROOMS = ["kitchen", "living room", "bedroom"]
EDITED = 2  # the living room, numbered from 1
TASKS = ("Put a chilled bread on the counter", "Turn on the lamp by the sofa", "Put the book on the bed",
         "Put a mug in the coffee machine")
SHIFT = 0.3  # m, the move


def timed(call):
    t0 = time.perf_counter()
    out = call()
    return out, time.perf_counter() - t0


def edits_of(plan, layout) -> dict[str, list]:
    """The three edits of a room: its first object moved, its line made `middle`, and moved then re-placed around."""
    first = plan.objects[0].id
    p = layout.placement(first)
    move = Move(object=first, x=min(p.x + SHIFT, plan.room.width), z=p.z)
    text = re.sub(rf"(?m)^{re.escape(first)} \|[^\n]*$", f"{first} | middle", plan.constraints)
    return {"move": [move], "constraints": [Constraints(text=text)],
            "re-place": [move, ReplaceAround(objects=[first])]}


def one_case(api: TestClient, pipeline: Pipeline, text: str, seed: int, house: bool) -> dict[str, tuple[float, float]]:
    """{what: (seconds through the API, seconds of apply_edits alone)}, `generate` with its own time twice."""
    body = {"instruction": text, "seed": seed, **({"room_type": "apartment", "rooms": ROOMS} if house else
                                                 {"room_type": pipeline.parse(text).room_type})}
    made, generate = timed(lambda: api.post("/generate", json=body).json())
    value = Apartment.model_validate(made["apartment"]) if house else Scene.model_validate(made["scene"])
    room = EDITED if house else None
    gen, key = room_of(value, room), "apartment" if house else "scene"
    out = {"generate": (generate, generate)}
    for what, edits in edits_of(gen.plan, gen.layout).items():
        request = {key: made[key], "edits": [json.loads(e.model_dump_json()) for e in edits],
                   **({"room": room} if house else {})}
        answer, through_api = timed(lambda: api.post("/edit", json=request))
        assert answer.status_code == 200, answer.text
        _, alone = timed(lambda: apply_edits(pipeline, value, edits, room))
        out[what] = (through_api, alone)
    if house:
        out["two rooms"] = two_rooms(api, value, made)
    return out


def two_rooms(api: TestClient, value: Apartment, made: dict) -> tuple[float, float]:
    """(seconds of one request moving the first object of room EDITED and of room 1, seconds of two requests)."""
    moves = [{**json.loads(edits_of(*_room(value, k))["move"][0].model_dump_json()), "room": k} for k in (EDITED, 1)]
    answer, one = timed(lambda: api.post("/edit", json={"apartment": made["apartment"], "edits": moves}))
    assert answer.status_code == 200, answer.text

    def two():
        first = api.post("/edit", json={"apartment": made["apartment"], "edits": moves[:1]}).json()
        return api.post("/edit", json={"apartment": first["apartment"], "edits": moves[1:]}).json()
    both, twice = timed(two)
    assert both["apartment"] == answer.json()["apartment"]
    return one, twice


def _room(value: Apartment, k: int):
    gen = room_of(value, k)
    return gen.plan, gen.layout


def main() -> None:
    pipeline = Pipeline(parser=RuleParser())
    with tempfile.TemporaryDirectory() as tmp:
        api = TestClient(create_app(Store(f"sqlite:///{tmp}/bench.db"), pipeline))
        one_case(api, pipeline, TASKS[0], N, True)  # not timed: loads the placer's network and warms the caches
        runs = {house: [one_case(api, pipeline, TASKS[k % len(TASKS)], k, house) for k in range(N)]
                for house in (False, True)}
    print(f"{N} tasks, each as its own single room and as an apartment ({', '.join(ROOMS)}; room {EDITED} edited), "
          "rule parser, plan2place; p50 (p90) ms through the API; in brackets apply_edits alone; x: p50 / p50 of "
          "POST /generate of the same values, same run")
    for house, label in ((False, "single room"), (True, "apartment")):
        gen = [r["generate"][0] for r in runs[house]]
        print(f"  {label}: POST /generate {1000 * quantile(gen, .5):6.0f} ({1000 * quantile(gen, .9):6.0f})")
        for what in ("move", "constraints", "re-place"):
            api_s, alone = [r[what][0] for r in runs[house]], [r[what][1] for r in runs[house]]
            print(f"    POST /edit {what:12s} {1000 * quantile(api_s, .5):6.0f} ({1000 * quantile(api_s, .9):6.0f})"
                  f"  [{1000 * quantile(alone, .5):5.0f}]  {quantile(api_s, .5) / quantile(gen, .5):.2f} x")
    one, two = [r["two rooms"][0] for r in runs[True]], [r["two rooms"][1] for r in runs[True]]
    print(f"  apartment, a move in each of two rooms: one request {1000 * quantile(one, .5):.0f} "
          f"({1000 * quantile(one, .9):.0f}), two requests {1000 * quantile(two, .5):.0f} "
          f"({1000 * quantile(two, .9):.0f}), {quantile(one, .5) / quantile(two, .5):.2f} x")


if __name__ == "__main__":
    main()
