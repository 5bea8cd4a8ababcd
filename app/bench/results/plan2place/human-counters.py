"""How the `human` set models iTHOR's L- and U-shaped counters: as one filled box (models.datasets.hard_sets reads each
object's axis-aligned bounding box). For every counter of a `human` plan that is at least `WIDE` m deep both ways
(a straight run is about 0.6-0.8 m deep), the share of the room's floor its box covers, and the share of the box that
something stands under or rests on (cabinets, drawers, a dishwasher, the stove's burners, the sink, or an object
whose parent is the counter; each box grown by `SLACK`): an L's or a U's inner corner holds none of those, so a low
share marks floor the box claims and the real counter leaves free. Also how many of the bench's runs left the
counter out (any solver). Reads the stored `human` set and app/bench/results/placement-human/results.json; writes
human-counters.md beside this script: PYTHONPATH=. python app/bench/results/plan2place/human-counters.py"""

import json
from pathlib import Path

import numpy as np

from models.datasets.constraint_sets import load_dataset
from models.world.catalogue import ithor_scenes

HERE = Path(__file__).resolve().parent
RUNS = HERE.parent / "placement-human" / "results.json"
WIDE = 1.0  # m
SLACK = 0.1  # m
CELL = 0.05  # m
SUPPORTS = {"Cabinet", "Drawer", "Dishwasher", "StoveBurner", "Sink"}


def _box(o: dict) -> tuple[float, float, float, float]:
    (w, _, d), x, z = o["size"], o["x"], o["z"]
    return x - w / 2, z - d / 2, x + w / 2, z + d / 2


def supported(scene: dict, counter: dict) -> float:
    """The share of `counter`'s box that a support stands under or an object on the counter rests over."""
    x0, z0, x1, z1 = _box(counter)
    xs, zs = np.meshgrid(np.arange(x0, x1, CELL) + CELL / 2, np.arange(z0, z1, CELL) + CELL / 2, indexing="ij")
    hit = np.zeros(xs.shape, bool)
    for o in scene["objects"]:
        if o["type"] in SUPPORTS or "CounterTop" in o["parents"]:
            a, b, c, d = _box(o)
            hit |= (xs >= a - SLACK) & (xs <= c + SLACK) & (zs >= b - SLACK) & (zs <= d + SLACK)
    return float(hit.mean())


def main() -> None:
    scenes = {s["scene"]: s for s in ithor_scenes()}
    runs = json.loads(RUNS.read_text())
    rows, records = [], load_dataset("human", None)
    for record in records:
        plan = record.plan
        scene = scenes[plan.id.removeprefix("human-")]
        counters = [o for o in scene["objects"] if o["type"] == "CounterTop" and set(o["parents"]) <= {"Floor"}]
        for k, obj in enumerate(o for o in plan.objects if o.type == "CounterTop"):
            if min(obj.size.x, obj.size.z) < WIDE:
                continue
            source = counters[k]  # the plan keeps the scene's floor-standing objects in the scene's order
            left_out = sum(1 for r in runs if r["plan"] == plan.id and obj.id in r.get("unplaced", {}))
            solved = sum(1 for r in runs if r["plan"] == plan.id)
            share = obj.size.x * obj.size.z / (plan.room.width * plan.room.depth)
            rows.append(f"| {plan.id} | {obj.id} | {obj.size.x:.2f} x {obj.size.z:.2f} | "
                        f"{plan.room.width:.2f} x {plan.room.depth:.2f} | {100 * share:.0f} % | "
                        f"{100 * supported(scene, source):.0f} % | {left_out} of {solved} |")
    kitchens = sum(1 for r in records if r.plan.room.type == "kitchen")
    lines = [f"Counters of the `human` plans at least {WIDE} m deep both ways: {len(rows)} in {kitchens} kitchens "
             "(models.datasets.hard_sets models each as its bounding box).", "",
             "| plan | counter | box (m) | room (m) | floor the box covers | box with something under or on it | "
             "runs leaving it out (all solvers) |", "| --- | --- | --- | --- | --- | --- | --- |", *rows]
    (HERE / "human-counters.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
