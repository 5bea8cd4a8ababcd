"""Would the companions' pass keep more habits (and realism rise) if its moves, like the polish's, could raise the
layout's energy a little? Plan2Place with the pass's `free_move` given an energy allowance of 0, 0.02, 0.05 and 0.15, on
16 diagnosis plans per set x 2 seeds (never the bench's or fresh plans); prints realism and the differences against 0.
Run from a tree's root:

    PYTHONPATH=. python app/bench/results/plan2place/companions-allowance.py > companions-allowance.txt
"""
import sys
from pathlib import Path

import numpy as np

from app.bench.placement import score
from models.placement import habits
from models.placement.base import get_solver

sys.path.insert(0, str(Path(__file__).parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

SHIPPED = habits.free_move
ALLOWANCE = {"value": 0.0}


def free_move(*args, **kwargs):
    return SHIPPED(*args, **{**kwargs, "allowance": ALLOWANCE["value"]})


habits.free_move = free_move

if __name__ == "__main__":
    solver = get_solver("plan2place")
    print("companions' pass with an energy allowance per move - without; 16 diagnosis plans x 2 seeds; x 100, energy as is")
    for ds in ("seen", "unseen_a", "unseen_b", "human"):
        plans = diagnosis_plans(ds, 16)
        rows = {}
        for value in (0.0, 0.02, 0.05, 0.15):
            ALLOWANCE["value"] = value
            rows[value] = [score(p, solver.solve(p, seed=seed)) for p in plans for seed in (0, 1)]
            diff = lambda m, f=100: f * float(np.mean([(b[m] or 0) - (a[m] or 0)  # noqa: E731
                                                       for a, b in zip(rows[0.0], rows[value])]))
            print(f"{ds} allowance {value}: realism {100 * np.mean([r['realism'] or 0 for r in rows[value]]):.2f} "
                  f"({diff('realism'):+.2f}), constraints {diff('constraint_satisfaction'):+.2f}, energy "
                  f"{diff('energy', 1):+.4f}, Key_NAV {diff('key_nav'):+.2f}", flush=True)
