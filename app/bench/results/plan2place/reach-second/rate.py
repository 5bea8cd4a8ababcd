"""How often the variant (variant.py) changes Plan2Place's layout on the placement bench's plans, seed 0 (a count of how
often the mechanism occurs, not a measure of the change): prints each set's plans whose layout differs.

    PYTHONPATH=. python app/bench/results/plan2place/reach-second/rate.py unseen_a seen unseen_b human dense
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from variant import SHIPPED, better_or_reaches  # noqa: E402

from app.bench.paired import fingerprint  # noqa: E402
from app.bench.placement import pick_records  # noqa: E402
from models.placement import get_solver, reorder  # noqa: E402

if __name__ == "__main__":
    solver = get_solver("plan2place")
    for ds in sys.argv[1:]:
        changed = []
        for r in pick_records(ds, 120 if ds == "human" else 100):
            prints = []
            for rule in (SHIPPED, better_or_reaches):
                reorder.better = rule
                prints.append(fingerprint(solver.solve(r.plan, seed=0)))
            if prints[0] != prints[1]:
                changed.append(r.plan.id)
        reorder.better = SHIPPED
        print(ds, "changed (seed 0):", changed, flush=True)
