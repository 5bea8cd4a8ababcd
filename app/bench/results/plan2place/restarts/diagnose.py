"""Solving again from another random state where objects are left out (models.placement.restarts), against the placer
without it, on the diagnosis plans (20 per set x 2 seeds; never the bench's or fresh plans), Plan2Place and greedy
alternating in one process; writes `diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/restarts/diagnose.py [SET ...]
"""
import sys
from pathlib import Path

from app.bench.gates import diagnose
from models.placement import restarts


def without(ep, again, observer=None):
    """The placer as it was: no restart."""
    return ep


if __name__ == "__main__":
    print(diagnose(Path(__file__).parent, "restarts", restarts, "restarted",
                   {"without": without, "restarts": restarts.restarted}, ("plan2place", "greedy"),
                   sys.argv[1:] or ("dense", "human")))
