"""The reach-kept solve with a third solve that places first the objects it left out for reach (variant.py), against
the shipped one, on the diagnosis plans (20 per set x 2 seeds; never the bench's or fresh plans), Plan2Place and
greedy alternating in one process; writes `diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/walls-first/diagnose.py [SET ...]
"""
import sys
from pathlib import Path

from app.bench.gates import diagnose
from models.placement import reach_kept
from variant import walls_first

if __name__ == "__main__":
    print(diagnose(Path(__file__).parent, "walls-first", reach_kept, "solve_keeping",
                   {"shipped": reach_kept.solve_keeping, "walls-first": walls_first}, ("plan2place", "greedy"),
                   sys.argv[1:] or ("dense", "human")))
