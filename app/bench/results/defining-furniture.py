"""How often a room lacks the furniture that makes it its type (`RoomSpec.defining`: a bedroom's bed, a kitchen's
fridge and counter...): in the stored constraint datasets (built without the rule, kept so) and in rooms the room
planner makes for a one-object task, seeds 0-199, with the rule (the default) and without it (`as_stored`). Writes
defining-furniture.txt beside this script:  PYTHONPATH=. python app/bench/results/defining-furniture.py"""

from pathlib import Path

from models.datasets import load_dataset
from models.planning import RoomPlanner
from models.planning.room_planner import RoomPlannerSettings
from models.values import TaskGraph
from models.world.rooms import ROOM_SPECS

SEEDS = 200
TYPES = [room for room, spec in ROOM_SPECS.items() if spec.defining]


def lacking(plans) -> str:
    """Share of the plans that lack one of their room type's defining types."""
    plans = list(plans)
    if not plans:
        return "-"
    short = sum(not set(ROOM_SPECS[p.room.type].defining) <= {o.type for o in p.objects} for p in plans)
    return f"{100 * short / len(plans):.0f} %"


def planned(room: str, defining: bool) -> list:
    graph = TaskGraph.model_validate({"instruction": "Pick up the apple", "room_type": room,
                                      "task_type": "pick_and_place_simple", "objects": [{"type": "Apple", "roles": ["key"]}]})
    planner = RoomPlanner(RoomPlannerSettings(as_stored=not defining))
    return [planner.plan(graph, seed) for seed in range(SEEDS)]


def main() -> str:
    lines = ["rooms lacking the furniture that makes them their type (share of the rooms of the type)", "",
             "| rooms | " + " | ".join(f"{r} ({', '.join(ROOM_SPECS[r].defining)})" for r in TYPES) + " |",
             "| --- |" + " --- |" * len(TYPES)]
    for name in ("seen", "unseen_a", "unseen_b"):
        plans = [r.plan for r in load_dataset(name)]
        lines.append(f"| stored `{name}` ({len(plans)} plans) | "
                     + " | ".join(lacking(p for p in plans if p.room.type == r) for r in TYPES) + " |")
    for defining in (False, True):
        lines.append(f"| planned, seeds 0-{SEEDS - 1}, {'with' if defining else 'without'} the rule | "
                     + " | ".join(lacking(planned(r, defining)) for r in TYPES) + " |")
    return "\n".join(lines)


if __name__ == "__main__":
    text = main()
    (Path(__file__).with_suffix(".txt")).write_text(text + "\n")
    print(text)
