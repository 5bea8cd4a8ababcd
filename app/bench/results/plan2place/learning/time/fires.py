"""Why training changes the time: how often each placer's episode leaves a constraint broken after the repairs and
so is solved again with the objects of broken constraints first (models.placement.reorder), and how often that
second solve is kept, on the same plans and seeds as run.py. Writes fires.md:
PYTHONPATH=. python app/bench/results/plan2place/learning/time/fires.py"""

import sys
from pathlib import Path

from app.bench.placement import pick_records
from models.placement import reorder
from models.placement.base import get_solver

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
from run import GREEDY, SEEDS, SETS, TRAINED, UNTRAINED  # noqa: E402 (beside this script)

COUNTS = {"runs": 0, "solved again": 0, "kept": 0}


def counting(inner):
    """`reorder.broken_first` counting the second solves it makes and keeps."""
    def broken_first(ep, repair, again, observer=None):
        def counted(first, seen):
            COUNTS["solved again"] += 1
            return again(first, seen)
        COUNTS["runs"] += 1
        best = inner(ep, repair, counted, observer)
        COUNTS["kept"] += best is not ep
        return best
    return broken_first


def main() -> str:
    reorder.broken_first = counting(reorder.broken_first)  # greedy.place_stepwise imports it at call time
    lines = [__doc__.split("\n\n")[0].replace("\n", " "), "",
             "| set | placer | runs | solved again | kept |", "| --- | --- | --- | --- | --- |"]
    for s, n in SETS.items():
        plans = [r.plan for r in pick_records(s, n)]
        for name in (GREEDY, TRAINED, UNTRAINED):
            solver = get_solver(name)
            COUNTS.update(dict.fromkeys(COUNTS, 0))
            for seed in range(SEEDS):
                for plan in plans:
                    solver.solve(plan, seed=seed)
            lines.append(f"| `{s}` | {name} | {COUNTS['runs']} | {COUNTS['solved again']} | {COUNTS['kept']} |")
            print(lines[-1], flush=True)
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    (HERE / "fires.md").write_text(text := main())
    print(text)
