"""An experiment, not a solver: Plan2Place with the front clearance soft, as MILP and Z3 have it (the hard filter
always relaxed, the energy's E_aff counting every strip a candidate blocks), measured as blocked-fronts.py measures
the solvers, on the same plans. How much of the `dense` constraints gap do the strips explain? Run from the root:
python app/bench/results/plan2place/blocked-fronts-soft.py dense,unseen_a,seen | grep '^|' > blocked-fronts-soft.md"""
import runpy
import sys

import models.placement.greedy as G
import models.placement.moves as M
import models.placement.polish as P
from models.placement.candidates import Shared


class SoftShared(Shared):  # the energy then always counts the strips a candidate blocks (E_aff)
    @property
    def zones_clear(self):
        return False

    @zones_clear.setter
    def zones_clear(self, value):
        pass


def soften() -> None:
    """Patch this process's placers: every hard filter relaxed, E_aff always computed."""
    strict_filter = G.hard_filter

    def relaxed(scorer, obj, placed, cands, swept, strict=True):
        return strict_filter(scorer, obj, placed, cands, swept, False)

    G.hard_filter = M.hard_filter = P.hard_filter = relaxed
    G.Shared = SoftShared


if __name__ == "__main__":
    soften()
    sys.argv = ["blocked-fronts.py", sys.argv[1], "plan2place"]
    runpy.run_path("app/bench/results/plan2place/blocked-fronts.py", run_name="__main__")
