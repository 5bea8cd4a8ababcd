"""Solving again with every task object kept reachable (models.placement.reach_kept) against not (gate.py's
`switched_off`; the module's `ROUNDS` 0 when this ran), on the diagnosis plans (20 per set x 2 seeds; never the
bench's or fresh plans), Plan2Place and greedy alternating in one process; writes `diagnose.md` and `diagnose.json`
here:

    PYTHONPATH=. python app/bench/results/plan2place/reach-kept/diagnose.py [SET ...]
"""
import sys
from pathlib import Path

from app.bench.gates import SETS, diagnose
from gate import switched_off
from models.placement import reach_kept

if __name__ == "__main__":
    print(diagnose(Path(__file__).parent, "reach-kept", reach_kept, "solve_keeping",
                   {"without": switched_off, "reach-kept": reach_kept.solve_keeping}, ("plan2place", "greedy"),
                   sys.argv[1:] or SETS))
