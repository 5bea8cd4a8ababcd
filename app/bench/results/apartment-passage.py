"""Rooms an apartment's robot must cross: placed once, or again with the next seeds while the furniture cuts a door
off from another (`Pipeline.place_passable`, up to PASSABLE_TRIES layouts), on the 30 instructions of `h3ds bench
generate --room-type apartment` (rule parser, seed i for the i-th), DFS and Plan2Place. Counts the rooms with two or
more doors whose doors stay cut off, the robot's plan meeting ALFRED's goal on the exported house (from the
entrance), Key_NAV through the doors, and the placing time. Writes apartment-passage.txt beside this script:
  H3DS_PARSER=rules PYTHONPATH=. python app/bench/results/apartment-passage.py"""

import statistics
from pathlib import Path

import app.pipeline as pipeline_module
from app.bench.generate import pick_instructions
from app.pipeline import Pipeline
from models.energy.navigation import doors_joined
from models.exports.apartment import apartment_house
from models.interaction import check_plan
from models.interaction.apartment import apartment_robot_plan
from models.scene.assemble import footprint_boxes

N = 30


def run(solver: str, tries: int) -> str:
    pipeline_module.PASSABLE_TRIES = tries
    pipeline = Pipeline(solver=solver)
    crossed = cut = goals = 0
    nav, spent = [], 0.0
    for i, (instruction, _) in enumerate(pick_instructions(N)):
        apartment = pipeline.generate_apartment(instruction, None, seed=i)
        house = apartment_house(apartment)
        goals += check_plan(house, apartment_robot_plan(apartment, house), apartment.task_graph).ok
        spent += sum(layout.timing.total_s for layout in apartment.layouts)
        for plan, layout in zip(apartment.plans, apartment.layouts):
            if len(plan.room.doors) > 1:
                crossed += 1
                cut += not doors_joined(plan.room, footprint_boxes(layout.placements))
        nav += [apartment.key_nav] if apartment.key_nav is not None else []
    return (f"| {solver} | {tries} | {cut} of {crossed} | {goals} of {N} | {100 * statistics.mean(nav):.1f} | "
            f"{1000 * spent / N:.0f} |")


def main() -> str:
    lines = [f"rooms with two or more doors whose doors stay cut off, on the {N} apartments of `bench generate "
             "--room-type apartment`", "", "| solver | layouts tried | rooms cut | robot plan meets the goal | "
             "Key_NAV through doors | placing ms per apartment |", "| --- | --- | --- | --- | --- | --- |"]
    for solver in ("dfs", "plan2place"):
        for tries in (1, 4):
            lines.append(run(solver, tries))
    return "\n".join(lines)


if __name__ == "__main__":
    text = main()
    Path(__file__).with_suffix(".txt").write_text(text + "\n")
    print(text)
