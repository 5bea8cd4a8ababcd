"""The `h3ds` command line of interfaces.md, including how it refuses bad input."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from app.cli import main

H3DS = [str(Path(sys.executable).parent / "h3ds")]


def run(args, capsys):
    code = main(args)
    out, err = capsys.readouterr()
    return code, out, err


def test_installed_command_generates_all_five_files(tmp_path):
    out = tmp_path / "bread"
    proc = subprocess.run(H3DS + ["generate", "Put a chilled bread on the counter", "--room-type", "kitchen",
                                  "--out", str(out)], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in out.iterdir()) == sorted(
        ["task_graph.json", "plan.json", "layout.json", "house.json", "scene.glb", "scene.json"])
    house = json.loads((out / "house.json").read_text())
    types = {o["id"].split("|")[0] for o in house["objects"]} | \
            {c["id"].split("|")[0] for o in house["objects"] for c in o["children"]}
    assert {"Fridge", "CounterTop", "Bread"} <= types


def test_parse_prints_the_task_graph(capsys):
    code, out, _ = run(["parse", "Put a chilled bread on the counter", "--room-type", "kitchen", "--json"], capsys)
    graph = json.loads(out)
    assert code == 0 and graph["task_type"] == "pick_cool_then_place_in_recep"


def test_parse_batch_keeps_ids_and_reports_bad_lines(tmp_path, capsys):
    src = tmp_path / "in.jsonl"
    src.write_text('{"id": "a", "instruction": "Put a mug in the sink"}\n'
                   '{"id": "b", "instruction": "", "room_type": "kitchen"}\n'
                   '{"id": "c", "instruction": "Look at the book under the lamp", "room_type": "Bedroom"}\n')
    dst = tmp_path / "out.jsonl"
    assert run(["parse", "--batch", str(src), "--out", str(dst)], capsys)[0] == 0
    rows = [json.loads(line) for line in dst.read_text().splitlines()]
    assert [r["id"] for r in rows] == ["a", "b", "c"]
    assert "empty" in rows[1]["error"] and rows[2]["room_type"] == "bedroom"


def test_place_one_and_many(tmp_path, capsys):
    run(["generate", "Put a chilled bread on the counter", "--room-type", "kitchen", "--out", str(tmp_path / "g")],
        capsys)
    plan = json.loads((tmp_path / "g" / "plan.json").read_text())
    second = tmp_path / "p2.json"
    second.write_text(json.dumps({**plan, "id": "second"}))
    code, out, _ = run(["place", str(tmp_path / "g" / "plan.json"), "--solver", "dfs", "--seed", "4"], capsys)
    assert code == 0 and json.loads(out)["seed"] == 4
    code, _, _ = run(["place", str(tmp_path / "g" / "plan.json"), str(second), "--out-dir", str(tmp_path / "many")],
                     capsys)
    assert code == 0 and sorted(p.name for p in (tmp_path / "many").iterdir()) == ["scene-0.json", "second.json"]


def test_place_keeps_the_poses_of_a_hand_edited_layout(tmp_path, capsys):
    """--keep: a layout edited by hand (one object moved, the ones to place again deleted) is kept as it is."""
    run(["generate", "Put a chilled bread on the counter", "--room-type", "kitchen", "--out", str(tmp_path / "g")],
        capsys)
    layout = json.loads((tmp_path / "g" / "layout.json").read_text())
    kept = layout["placements"][:2]
    kept[0] = {**kept[0], "x": round(kept[0]["x"] + 0.05, 4)}
    (tmp_path / "edited.json").write_text(json.dumps({**layout, "placements": kept}))
    code, out, _ = run(["place", str(tmp_path / "g" / "plan.json"), "--keep", str(tmp_path / "edited.json")], capsys)
    again = {p["id"]: p for p in json.loads(out)["placements"]}
    assert code == 0 and len(again) == len(layout["placements"])
    for p in kept:
        assert (again[p["id"]]["x"], again[p["id"]]["z"], again[p["id"]]["rotation"]) == (p["x"], p["z"], p["rotation"])
    stranger = {**layout, "placements": [{**kept[0], "id": "sofa-9"}]}
    (tmp_path / "stranger.json").write_text(json.dumps(stranger))
    code, _, err = run(["place", str(tmp_path / "g" / "plan.json"), "--keep", str(tmp_path / "stranger.json")], capsys)
    assert code == 2 and "not objects of plan scene-0: sofa-9" in err
    away = {**layout, "placements": [{**kept[0], "z": -3.0}]}  # a pose outside the room: an error, not an object outside
    (tmp_path / "away.json").write_text(json.dumps(away))
    code, _, err = run(["place", str(tmp_path / "g" / "plan.json"), "--keep", str(tmp_path / "away.json")], capsys)
    assert code == 2 and f"room of plan scene-0: {kept[0]['id']} at ({kept[0]['x']}, -3.0)" in err
    (tmp_path / "bad.json").write_text('{"placements": 3}')
    code, _, err = run(["place", str(tmp_path / "g" / "plan.json"), "--keep", str(tmp_path / "bad.json")], capsys)
    assert code == 2 and "bad.json" in err and err.count("\n") == 1


BAD_PLANS = {
    "not-json.json": (b"{ this is not json", "not valid JSON"),
    "binary.json": (bytes(range(256)), "not valid JSON"),
    "list.json": (b"[1, 2]", "must be a JSON object"),
    "negative.json": (json.dumps({"id": "p", "room": {"type": "kitchen", "width": 3, "depth": 3},
                                  "objects": [{"id": "a", "type": "Chair", "size": {"x": -1, "y": 1, "z": 1}}]}).encode(),
                      "objects.0.size.x"),
    "missing.json": (json.dumps({"id": "p", "objects": []}).encode(), "room"),
}


@pytest.mark.parametrize("name", sorted(BAD_PLANS))
def test_bad_plans_exit_2_with_one_line(tmp_path, capsys, name):
    content, message = BAD_PLANS[name]
    (tmp_path / name).write_bytes(content)
    code, _, err = run(["place", str(tmp_path / name)], capsys)
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("args,message", [
    (["parse", ""], "empty"),
    (["parse", "x" * 10_000], "10000 characters"),
    (["parse", "put \x01\x02 away"], "binary"),
    (["generate", "Put a mug in the sink", "--room-type", "spaceship", "--out", "/tmp/x"], "unknown room type"),
    (["generate", "Put a mug in the sink", "--out", "/tmp/x"], "--room-type"),
    (["place", "/no/such/plan.json"], "cannot read"),
    (["frobnicate"], "invalid choice"),
])
def test_bad_input_exits_2_without_traceback(capsys, args, message):
    code, _, err = run(args, capsys)
    assert code == 2 and message in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_unknown_solver(tmp_path, capsys):
    run(["generate", "Put a mug in the sink", "--room-type", "kitchen", "--out", str(tmp_path)], capsys)
    code, _, err = run(["place", str(tmp_path / "plan.json"), "--solver", "annealing"], capsys)
    assert code == 2 and "unknown solver 'annealing'" in err


@pytest.mark.parametrize("command", ["place", "generate"])
def test_help_says_what_each_solver_does(command):
    from models.placement import SOLVERS
    from models.placement.base import summaries
    proc = subprocess.run(H3DS + [command, "--help"], capture_output=True, text=True, timeout=60)
    listed = proc.stdout.split("solvers:\n", 1)[1].splitlines()
    assert proc.returncode == 0 and [line.split()[0] for line in listed] == sorted(SOLVERS)
    assert all(len(line.split(None, 1)[1]) > 20 for line in listed)  # a sentence each, not an empty docstring
    assert summaries()["plan2place_all_objects"] in proc.stdout


def test_stdout_carries_json_alone_with_the_milp_solver(tmp_path, capsys):
    """HiGHS prints a banner on the C-level stdout at a process's first model; `h3ds place` must keep stdout the
    layout (or the steps' JSON lines) all the same, in a real process where MILP makes its first model."""
    run(["generate", "Put a mug in the sink", "--room-type", "kitchen", "--parser", "rules", "--out", str(tmp_path)],
        capsys)
    plan = str(tmp_path / "plan.json")
    proc = subprocess.run(H3DS + ["place", plan, "--solver", "milp"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0 and json.loads(proc.stdout)["solver"] == "milp"
    proc = subprocess.run(H3DS + ["place", plan, "--solver", "milp", "--steps", "-", "--out", str(tmp_path / "l.json")],
                          capture_output=True, text=True, timeout=120)
    steps = [json.loads(line) for line in proc.stdout.splitlines()]
    assert proc.returncode == 0 and steps and all("object" in s for s in steps)
    assert "HiGHS" in proc.stderr  # the banner went to stderr, not away


def test_binary_instruction_through_the_real_process():
    proc = subprocess.run(H3DS + ["parse", "\x7f\x01\x02"], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr and proc.stderr.count("\n") == 1


def test_parse_policy_picks_how_rules_and_model_combine(capsys, monkeypatch):
    """--policy builds the combined parser with that policy; it is refused for another parser."""
    from models.language import combined
    made = []
    monkeypatch.setattr(combined.CombinedParser, "parse", lambda self, text, room=None: made.append(self.policy) or
                        combined.RuleParser().parse(text, room))
    code, out, _ = run(["parse", "Put a mug in the sink", "--room-type", "kitchen", "--policy", "rules-first-strict",
                        "--json"], capsys)
    assert code == 0 and made == ["rules-first-strict"] and json.loads(out)["objects"]
    code, _, err = run(["parse", "Put a mug in the sink", "--parser", "rules", "--policy", "lm-first"], capsys)
    assert code == 2 and "--policy is for --parser combined, not rules" in err
    code, _, err = run(["parse", "Put a mug in the sink", "--policy", "best"], capsys)
    assert code == 2 and "invalid choice: 'best'" in err


def test_the_room_type_inferred_from_the_instruction(tmp_path, capsys):
    """`--room-type infer` (as the studio's Room type dropdown offers): the parser reads the room from the task."""
    code, out, _ = run(["parse", "Look at the book under the lamp", "--room-type", "Infer"], capsys)
    assert code == 0 and json.loads(out)["room_type"] == "bedroom"
    code, _, _ = run(["generate", "Put a chilled bread on the counter", "--room-type", "infer", "--out",
                      str(tmp_path / "g")], capsys)
    graph = json.loads((tmp_path / "g" / "task_graph.json").read_text())
    plan = json.loads((tmp_path / "g" / "plan.json").read_text())
    assert code == 0 and graph["room_type"] == "kitchen" and plan["room"]["type"] == "kitchen"
