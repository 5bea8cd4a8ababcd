"""The second solve kept also where it reaches more task objects at a lower energy (variant.py), against the shipped
rule, on the diagnosis plans (20 per set x 2 seeds; never the bench's or fresh plans), Plan2Place and greedy
alternating in one process; writes `diagnose.md` and `diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/reach-second/diagnose.py [SET ...]
"""
import sys
from pathlib import Path

from app.bench.gates import diagnose
from models.placement import reorder
from variant import SHIPPED, better_or_reaches

if __name__ == "__main__":
    print(diagnose(Path(__file__).parent, "reach-second", reorder, "better",
                   {"shipped": SHIPPED, "reach-second": better_or_reaches}, ("plan2place", "greedy"),
                   sys.argv[1:] or ("seen", "unseen_a", "unseen_b", "dense", "human")))
