"""POST /place/steps over a real HTTP server (uvicorn on loopback): the placer's steps arrive one JSON line each
while it is still placing, then the layout, which is POST /place's; a failing solver ends the stream with an
error line; bad requests are 422s before anything is placed."""

import json
import threading
import time

import httpx
import pytest
import uvicorn

from app.api import MAX_TOP, create_app
from frontend.server import free_port
from models.placement import base, get_solver
from studio_db import Store

WAIT_S = 60  # how long the gated solver waits for the client to read its first step


@pytest.fixture(scope="module")
def plan(pipeline):
    return json.loads(pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0).plan.model_dump_json())


@pytest.fixture
def api(tmp_path, pipeline):
    port = free_port("127.0.0.1", 18900)
    server = uvicorn.Server(uvicorn.Config(create_app(Store(f"sqlite:///{tmp_path / 'studio.db'}"), pipeline),
                                           host="127.0.0.1", port=port, log_level="warning"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    while not server.started:
        time.sleep(0.02)
    with httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=120) as client:
        yield client
    server.should_exit = True
    thread.join(10)


def streamed(api, body: dict, **params) -> list[dict]:
    with api.stream("POST", "/place/steps", json=body, params=params) as r:
        assert r.status_code == 200 and r.headers["content-type"] == "application/x-ndjson"
        return [json.loads(line) for line in r.iter_lines() if line]


def test_steps_then_the_layout_of_post_place(api, plan):
    lines = streamed(api, {"plan": plan, "seed": 1})
    *steps, last = lines
    layout = api.post("/place", json={"plan": plan, "seed": 1}).json()
    timing = lambda d: {k: v for k, v in d.items() if k != "timing"}  # noqa: E731 - the rest is the same placement
    assert timing(last["layout"]) == timing(layout) and layout["solver"] == "plan2place"
    assert [s["step"] for s in steps] == list(range(1, len(steps) + 1))
    final = {s["object"]: (s["x"], s["z"], s["rotation"]) for s in steps}  # each object's last step
    assert final == {p["id"]: (p["x"], p["z"], p["rotation"]) for p in layout["placements"]}
    assert all(len(s["top"]) == min(5, s["legal"]) and set(s["terms"]) >= {"rel", "total"} for s in steps)


def test_every_candidate_for_a_heat_map_and_bad_requests(api, plan):
    steps = streamed(api, {"plan": plan, "solver": "greedy"}, top=MAX_TOP)[:-1]
    assert all(len(s["top"]) == s["legal"] for s in steps) and max(s["legal"] for s in steps) > 5
    assert api.post("/place/steps", json={"plan": plan}, params={"top": MAX_TOP + 1}).status_code == 422
    bad = api.post("/place/steps", json={"plan": plan, "solver": "best"})
    assert bad.status_code == 422 and "unknown solver 'best'" in bad.text
    bad = api.post("/place/steps", json={"plan": plan, "keep": {"sofa-9": [1, 1, 0]}})
    assert bad.status_code == 422 and "sofa-9" in bad.text


class Gated:
    """Greedy that, after its first step, waits until the test has read that step from the stream (or fails)."""

    name = "gated"

    def __init__(self, read: threading.Event, fail: bool = False):
        self.read, self.fail = read, fail

    def solve(self, plan, seed=0, time_budget_s=None, observer=None, fixed=None):
        def first_then_wait(step):
            observer(step)
            if not self.read.wait(WAIT_S):
                raise TimeoutError("the client never got the first step while the placer was running")
            if self.fail:
                raise RuntimeError("the placer broke down")
        return get_solver("greedy").solve(plan, seed, time_budget_s, first_then_wait, fixed)


@pytest.mark.parametrize("fail", [False, True])
def test_steps_stream_while_the_placer_runs_and_a_failure_ends_the_stream(api, plan, monkeypatch, fail):
    read = threading.Event()
    monkeypatch.setitem(base.SOLVERS, "gated", lambda: Gated(read, fail))
    with api.stream("POST", "/place/steps", json={"plan": plan, "solver": "gated"}) as r:
        lines = r.iter_lines()
        first = json.loads(next(lines))
        read.set()  # the placer was held after its first step until now: that line came while it ran
        rest = [json.loads(line) for line in lines if line]
    assert first["step"] == 1 and first["object"] in {o["id"] for o in plan["objects"]}
    if fail:
        assert rest == [{"error": "RuntimeError: the placer broke down"}]
    else:
        assert "layout" in rest[-1] and rest[-1]["layout"]["solver"] == "greedy"


def test_the_exact_finish_arrives_as_steps_after_the_placers(api):
    """`plan2place_exact` on the iTHOR bedroom where Plan2Place leaves a constraint broken: Z3's poses come last, one
    step per object, the first emptying the room, none with candidates (a whole-room solve has no heat-map)."""
    from models.datasets import load_dataset
    from models.placement.exact_finish import EXACT
    bedroom = next(r.plan for r in load_dataset("human") if r.plan.id == "human-FloorPlan313")
    *steps, last = streamed(api, {"plan": json.loads(bedroom.model_dump_json()), "solver": "plan2place_exact"})
    exact = [s for s in steps if s["why"] == EXACT]
    assert len(exact) == len(bedroom.objects) and steps[-len(exact):] == exact and exact[0]["restart"]
    assert not any(s["restart"] for s in exact[1:]) and all(s["candidates"] == 0 for s in exact)
    assert {s["object"]: (s["x"], s["z"], s["rotation"]) for s in exact} == \
        {p["id"]: (p["x"], p["z"], p["rotation"]) for p in last["layout"]["placements"]}
