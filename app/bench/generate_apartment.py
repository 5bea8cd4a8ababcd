"""`h3ds bench generate --room-type apartment`: the whole apartment pipeline on ALFRED instructions.

Per instruction, after one warm-up: generate (parse, rooms, per-room plans and placement, floorplan,
navigation through the doors) plus the house JSON and GLB in memory; each room's placement time; the
apartment's Key_NAV; and, as the baseline, the same instruction generated as one room of its own type
(its time with the same exports, and its Key_NAV from the doorway).
"""

from __future__ import annotations

import statistics
import time

from app.bench.generate import pick_instructions, placers, quantile
from app.pipeline import Pipeline
from models.language import RuleParser
from models.exports.apartment import apartment_glb, apartment_house
from models.exports.glb import to_glb
from models.exports.procthor_house import to_house
from models.interaction import check_plan, robot_plan
from models.interaction.apartment import apartment_robot_plan
from models.metrics import scene_metrics
from models.planning.apartment_planner import parse_rooms


def _ms(values: list[float]) -> str:
    return f"p50 {1000 * quantile(values, .5):8.1f} ms   p90 {1000 * quantile(values, .9):8.1f} ms"


def main(args) -> int:
    for solver in placers(args):
        run(Pipeline(parser=RuleParser(), solver=solver), args)  # the rules, as the figures in the README
    return 0


def run(pipeline: Pipeline, args) -> None:
    rooms = parse_rooms(args.rooms)
    items = pick_instructions(args.n)
    pipeline.generate_apartment(items[0][0], rooms, seed=0)  # warm-up: catalogue load, imports
    totals, singles, per_room, per_object, counts, key_nav, single_nav, skipped = [], [], [], [], [], [], [], 0
    unplaced = objects = 0
    plan_s, goals, single_goals = [], 0, 0  # the robot's plan on the exported house, checked symbolically
    lamp_alone = 0  # task graphs of a lamp alone, whose goal is its light (models.interaction.robot_plan)
    for i, (instruction, room) in enumerate(items):
        try:
            pipeline.parse(instruction, room)
        except ValueError:
            skipped += 1
            continue
        t0 = time.perf_counter()
        apartment = pipeline.generate_apartment(instruction, rooms, seed=i)
        house, _ = apartment_house(apartment), apartment_glb(apartment)
        totals.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        plan = apartment_robot_plan(apartment, house)
        plan_s.append(time.perf_counter() - t0)
        goals += check_plan(house, plan, apartment.task_graph).ok
        lamp_alone += apartment.task_graph.lamp_alone
        per_room += [layout.timing.total_s for layout in apartment.layouts]
        per_object += [layout.timing.per_object_s for layout in apartment.layouts]
        counts.append(len(apartment.scenes))
        key_nav += [apartment.key_nav] if apartment.key_nav is not None else []
        unplaced += len(apartment.unplaced)
        objects += sum(len(p.objects) + len(rp.surface_objects) for p, rp in zip(apartment.plans,
                                                                                  apartment.plan.room_plans))
        t0 = time.perf_counter()
        gen = pipeline.generate(instruction, room, seed=i)
        house, _ = to_house(gen.scene), to_glb(gen.scene)
        singles.append(time.perf_counter() - t0)
        single_goals += check_plan(house, robot_plan(gen.scene, house), gen.task_graph).ok
        single_nav += [m.key_nav] if (m := scene_metrics(gen.plan, gen.layout)).key_nav is not None else []
    which = f"rooms {', '.join(rooms)}" if rooms else "2-5 rooms drawn from each task and seed"
    print(f"generate --room-type apartment on {len(totals)} ALFRED valid_unseen instructions ({skipped} unparseable "
          f"skipped), {pipeline.solver} placer, {which}")
    print(f"  rooms per apartment     mean {statistics.mean(counts):.1f} (min {min(counts)}, max {max(counts)}), "
          f"{len(per_room)} rooms in all")
    print(f"  generate wall time      {_ms(totals)}   (with house JSON and GLB)")
    print(f"  placing per room        {_ms(per_room)}")
    print(f"  placing share           {100 * sum(per_room) / sum(totals):5.1f} % of generate")
    print(f"  time per object         p50 {1000 * quantile(per_object, .5):8.2f} ms   p90 "
          f"{1000 * quantile(per_object, .9):8.2f} ms")
    print(f"  Key_NAV through doors   {100 * statistics.mean(key_nav):5.1f} (mean over {len(key_nav)} apartments; "
          f"{sum(k == 0 for k in key_nav)} at 0)")
    print(f"  unplaced objects        {unplaced} of {objects}")
    print(f"  robot plan (symbolic)   {_ms(plan_s)}   goal met in {goals} of {len(totals)} "
          f"(one room: {single_goals} of {len(totals)}; {lamp_alone} a lamp alone, the goal its light)")
    print(f"  baseline: one room      {_ms(singles)}   (the task's own room type, same exports) -> apartment / "
          f"room = {quantile(totals, .5) / quantile(singles, .5):.1f}x at p50")
    print(f"                          Key_NAV {100 * statistics.mean(single_nav):5.1f} from its doorway "
          f"({sum(k == 0 for k in single_nav)} at 0)")
