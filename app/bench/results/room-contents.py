"""How many of each furniture type a planned room holds, and how long its pieces are, against the 120 hand-designed
iTHOR rooms: the room planner as the stored datasets were built (`as_stored`: a count of pieces drawn first and filled
by frequency, repeats allowed, any asset of a type) and as it plans now (each type as often as iTHOR rooms hold it,
chairs after the dining table, each piece sized like one of the type in iTHOR rooms of the type), for a one-object
task, seeds 0-199. Writes room-contents.txt beside this script:
  PYTHONPATH=. python app/bench/results/room-contents.py"""

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


def ithor_rooms(room: str) -> list[list[tuple[str, float]]]:
    """Each iTHOR room of the type as (type, longer side of the footprint) per object."""
    return [[(o["type"], max(o["size"][0], o["size"][2])) for o in r["objects"]] for r in ithor_scenes()
            if r["room_type"] == room]


def planned_rooms(planner: RoomPlanner, room: str) -> list[list[tuple[str, float]]]:
    graph = TaskGraph.model_validate({"instruction": "Pick up the apple", "room_type": room, "task_type":
                                      "pick_and_place_simple", "objects": [{"type": "Apple", "roles": ["key"]}]})
    return [[(o.type, max(o.size.x, o.size.z)) for o in planner.plan(graph, seed).objects] for seed in range(SEEDS)]


def cell(rooms: list[Counter], name: str) -> str:
    """Mean count per room, and the most any room holds."""
    return f"{statistics.mean(r[name] for r in rooms):.2f} (max {max(r[name] for r in rooms)})"


def sizes_table(rooms: dict[str, list[list[tuple[str, float]]]], planned: set[str]) -> list[str]:
    """Median longer side of the pieces of each type, where iTHOR's rooms of the type hold it."""
    longest = {name: {t: [side for objs in rs for t2, side in objs if t2 == t] for t in planned}
               for name, rs in rooms.items()}
    shown = sorted(t for t in planned if longest["iTHOR"][t])
    lines = ["", "longer side of a piece (m), median:", "", "| type | " + " | ".join(rooms) + " |",
             "| --- |" + " --- |" * len(rooms)]
    gaps = dict.fromkeys(PLANNERS, 0.0)
    for t in shown:
        medians = {name: statistics.median(v[t]) if v[t] else None for name, v in longest.items()}
        lines.append(f"| {t} | " + " | ".join("-" if m is None else f"{m:.2f}" for m in medians.values()) + " |")
        for p in PLANNERS:
            gaps[p] += abs(medians[p] - medians["iTHOR"]) if medians[p] is not None else 0.0
    return lines + ["", "summed gap to iTHOR's medians over these types: "
                    + ", ".join(f"{p} {gap:.2f}" for p, gap in gaps.items()), ""]


def table(room: str) -> list[str]:
    rooms = {"iTHOR": ithor_rooms(room)} | {name: planned_rooms(p, room) for name, p in PLANNERS.items()}
    sets = {name: [Counter(t for t, _ in objs) for objs in rs] for name, rs in rooms.items()}
    planned = set().union(*sets["as stored"], *sets["now"])
    lines = [f"### {room} ({len(sets['iTHOR'])} iTHOR rooms, {SEEDS} planned)", "",
             "| type | " + " | ".join(sets) + " |", "| --- |" + " --- |" * len(sets)]
    gaps = dict.fromkeys(PLANNERS, 0.0)
    for name in sorted(planned):
        lines.append(f"| {name} | " + " | ".join(cell(rooms, name) for rooms in sets.values()) + " |")
        for p in PLANNERS:
            gaps[p] += abs(statistics.mean(r[name] for r in sets[p]) - statistics.mean(r[name] for r in sets["iTHOR"]))
    lines += ["", "summed gap to iTHOR's means over these types: "
              + ", ".join(f"{p} {gap:.2f}" for p, gap in gaps.items())]
    return lines + sizes_table(rooms, planned)


def main() -> str:
    lines = ["furniture per room: mean count (the most in one room), and the pieces' size, iTHOR against the room "
             "planner", ""]
    for room, spec in ROOM_SPECS.items():
        if spec.ithor:
            lines += table(room)
    return "\n".join(lines)


if __name__ == "__main__":
    text = main()
    Path(__file__).with_suffix(".txt").write_text(text + "\n")
    print(text)
