"""How many of each furniture type a planned room holds, against the 120 hand-designed iTHOR rooms: the room planner
as the stored datasets were built (`as_stored`: a count of pieces drawn first and filled by frequency, repeats
allowed) and as it plans now (each type as often as iTHOR rooms hold it), for a one-object task, seeds 0-199. Writes
room-contents.txt beside this script:  PYTHONPATH=. python app/bench/results/room-contents.py"""

import statistics
from collections import Counter
from pathlib import Path

from models.planning import RoomPlanner
from models.planning.room_planner import RoomPlannerSettings
from models.values import TaskGraph
from models.world.catalogue import ithor_scenes
from models.world.rooms import ROOM_SPECS

SEEDS = 200
PLANNERS = {"as stored": RoomPlanner(RoomPlannerSettings(as_stored=True)), "now": RoomPlanner()}


def ithor_rooms(room: str) -> list[Counter]:
    return [Counter(o["type"] for o in r["objects"]) for r in ithor_scenes() if r["room_type"] == room]


def planned_rooms(planner: RoomPlanner, room: str) -> list[Counter]:
    graph = TaskGraph.model_validate({"instruction": "Pick up the apple", "room_type": room,
                                      "task_type": "pick_and_place_simple", "objects": [{"type": "Apple", "roles": ["key"]}]})
    return [Counter(o.type for o in planner.plan(graph, seed).objects) for seed in range(SEEDS)]


def cell(rooms: list[Counter], name: str) -> str:
    """Mean count per room, and the most any room holds."""
    return f"{statistics.mean(r[name] for r in rooms):.2f} (max {max(r[name] for r in rooms)})"


def table(room: str) -> list[str]:
    sets = {"iTHOR": ithor_rooms(room)} | {name: planned_rooms(p, room) for name, p in PLANNERS.items()}
    planned = set().union(*sets["as stored"], *sets["now"])
    lines = [f"### {room} ({len(sets['iTHOR'])} iTHOR rooms, {SEEDS} planned)", "",
             "| type | " + " | ".join(sets) + " |", "| --- |" + " --- |" * len(sets)]
    gaps = dict.fromkeys(PLANNERS, 0.0)
    for name in sorted(planned):
        lines.append(f"| {name} | " + " | ".join(cell(rooms, name) for rooms in sets.values()) + " |")
        for p in PLANNERS:
            gaps[p] += abs(statistics.mean(r[name] for r in sets[p]) - statistics.mean(r[name] for r in sets["iTHOR"]))
    lines += ["", "summed gap to iTHOR's means over these types: "
              + ", ".join(f"{p} {gap:.2f}" for p, gap in gaps.items()), ""]
    return lines


def main() -> str:
    lines = ["furniture per room: mean count (the most in one room), iTHOR against the room planner", ""]
    for room, spec in ROOM_SPECS.items():
        if spec.ithor:
            lines += table(room)
    return "\n".join(lines)


if __name__ == "__main__":
    text = main()
    Path(__file__).with_suffix(".txt").write_text(text + "\n")
    print(text)
