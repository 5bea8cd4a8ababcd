"""Going back when an object finds no room (models.placement.backtrack) against not (`DEPTH` 0), on the diagnosis
plans (20 per set x 2 seeds; never the bench's or fresh plans), Plan2Place and greedy alternating in one process;
writes `diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/backtrack/diagnose.py [SET ...]
"""
import sys
from pathlib import Path

from app.bench.gates import SETS, diagnose
from models.placement import backtrack

if __name__ == "__main__":
    name = f"backtrack (DEPTH {backtrack.DEPTH}, TRIES {backtrack.TRIES})"
    print(diagnose(Path(__file__).parent, name, backtrack, "DEPTH", {"without": 0, "backtrack": backtrack.DEPTH},
                   ("plan2place", "greedy"), sys.argv[1:] or SETS))
