"""An experiment, not a solver: Plan2Place with the front clearance soft, as MILP and Z3 have it (the hard filter
always relaxed, the energy's E_aff counting every strip a candidate blocks), measured as blocked-fronts.py measures
the solvers, on the same plans. How much of the `dense` constraints gap do the strips explain? Run from the root:
python app/bench/results/plan2place/blocked-fronts-soft.py dense,unseen_a,seen | grep '^|' > blocked-fronts-soft.md"""
import sys, runpy
import models.placement.greedy as G
import models.placement.moves as M
orig = G.hard_filter
def relaxed(scorer, obj, placed, cands, swept, strict=True):
    return orig(scorer, obj, placed, cands, swept, False)
G.hard_filter = relaxed
M.hard_filter = relaxed
import models.placement.polish as P
P.hard_filter = relaxed
from models.placement.candidates import Shared
class SoftShared(Shared):  # the energy then always counts the strips a candidate blocks (E_aff)
    @property
    def zones_clear(self):
        return False
    @zones_clear.setter
    def zones_clear(self, value):
        pass
G.Shared = SoftShared
sys.argv = ["blocked-fronts.py", sys.argv[1], "plan2place"]
runpy.run_path("app/bench/results/plan2place/blocked-fronts.py", run_name="__main__")
