"""Placement as an iterator of steps, and `h3ds place --steps`."""

import json

import numpy as np
import pytest

from app.cli import main
from models.placement import PlacementStep, get_solver
from models.placement.stepping import TOP, Stepping, step_record


@pytest.fixture(scope="module")
def plan(pipeline):
    return pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=2).plan


def test_the_iterator_hands_over_the_observers_steps_and_the_layout(plan):
    seen: list[PlacementStep] = []
    layout = get_solver("plan2place").solve(plan, seed=1, observer=seen.append)
    stepping = Stepping(get_solver("plan2place"), plan, seed=1)
    steps = list(stepping)
    assert [(s.object_id, s.x, s.z, s.rotation, s.why) for s in steps] == \
        [(s.object_id, s.x, s.z, s.rotation, s.why) for s in seen]
    assert all(np.array_equal(a.scores, b.scores) for a, b in zip(steps, seen))
    assert stepping.layout.placements == layout.placements
    assert len(steps) >= len(plan.objects)  # every object once, then the repairs' moves


class Failing:
    """A placer that makes one step and then fails: what the iterator does with a solver's error."""
    name = "failing"

    def solve(self, plan, seed=0, time_budget_s=None, observer=None, fixed=None):
        observer(PlacementStep("a-0", 1.0, 1.0, 0.0, np.zeros((1, 3)), np.ones(1), {"total": 0.0}))
        raise RuntimeError("the placer broke")


def test_a_solver_error_comes_after_the_steps_made_before_it(plan):
    stepping, got = Stepping(Failing(), plan), []
    with pytest.raises(RuntimeError, match="the placer broke"):
        for step in stepping:
            got.append(step.object_id)
    assert got == ["a-0"] and stepping.layout is None


def test_a_step_record_lists_the_best_scored_legal_candidates():
    cands = np.array([[0.5, 0.5, 0.0], [1.0, 0.5, 90.0], [1.5, 0.5, 0.0], [2.0, 0.5, 0.0]] * 2)
    scores = np.array([0.1, 0.4, -np.inf, 0.2, 0.0, 0.3, -np.inf, 0.0])
    rec = step_record(PlacementStep("chair-0", 1.0, 0.5, 90.0, cands, scores, {"total": 0.25}, "why not"), 3)
    assert rec["step"] == 3 and rec["legal"] == 6 and rec["candidates"] == 8 and rec["why"] == "why not"
    assert rec["restart"] is False
    assert [r[-1] for r in rec["top"]] == [0.4, 0.3, 0.2, 0.1, 0.0][:TOP]
    assert rec["top"][0] == [1.0, 0.5, 90.0, 0.4]
    json.dumps(rec)


def test_place_command_writes_each_step_as_a_json_line(tmp_path, plan, capsys):
    (tmp_path / "plan.json").write_text(plan.model_dump_json())
    assert main(["place", str(tmp_path / "plan.json"), "--steps", str(tmp_path / "steps.jsonl"),
                 "--out", str(tmp_path / "layout.json")]) == 0
    steps = [json.loads(line) for line in (tmp_path / "steps.jsonl").read_text().splitlines()]
    layout = json.loads((tmp_path / "layout.json").read_text())
    assert layout["solver"] == "plan2place" and [s["step"] for s in steps] == list(range(1, len(steps) + 1))
    last = {s["object"]: (s["x"], s["z"], s["rotation"]) for s in steps}  # a repair's move replaces a pose
    assert last == {p["id"]: (p["x"], p["z"], p["rotation"]) for p in layout["placements"]}
    assert main(["place", str(tmp_path / "plan.json"), "--steps", "-", "--out", str(tmp_path / "l2.json")]) == 0
    assert len(capsys.readouterr().out.splitlines()) == len(steps)


@pytest.mark.parametrize("two_plans", [False, True])
def test_place_command_refuses_steps_it_cannot_write(tmp_path, plan, capsys, two_plans):
    """Steps on stdout with the layout on stdout too, or steps of several plans in one file: refused."""
    (tmp_path / "plan.json").write_text(plan.model_dump_json())
    plans = [str(tmp_path / "plan.json")] * (2 if two_plans else 1)
    where = ["--steps", str(tmp_path / "s.jsonl"), "--out-dir", str(tmp_path / "d")] if two_plans else ["--steps", "-"]
    assert main(["place", *plans, *where]) == 2
    assert "--steps takes one plan" in capsys.readouterr().err
    assert not (tmp_path / "s.jsonl").exists() and not (tmp_path / "d").exists()
