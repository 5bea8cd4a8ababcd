"""How many make-way options the objects Plan2Place leaves out on `dense` have: for each object left out after the
steps, the poses where at most `moves.MAX_BLOCKERS` placed objects stand in its way (`displacements` with no limit on
tries), and how many of those objects `make_room` then places; on the 20 `dense` diagnosis plans x 2 seeds. Run from a
tree's root:

    PYTHONPATH=. python app/bench/results/plan2place/dense-cnt/options.py > app/bench/results/plan2place/dense-cnt/options.txt
"""
import sys
from collections import Counter
from pathlib import Path

from models.placement import moves as M
from models.placement import repair as R
from models.placement.base import get_solver
from models.placement.greedy import NO_ROOM

sys.path.insert(0, str(Path(__file__).parent.parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

COUNT: Counter = Counter()
SHIPPED = R.make_room


def make_room(ep, observer=None):
    left = [o for o in ep.order if ep.failed.get(o.id) == NO_ROOM and o.id not in ep.problem.fixed]
    for obj in left:
        options = M.displacements(ep, obj, ep.scorer.bodies(obj)[0], ep.scorer.swept(obj), ep.placed, tries=10**6)
        COUNT["left out after the steps"] += 1
        COUNT["with a make-way option"] += bool(options)
        COUNT["make-way options"] += len(options)
    done = SHIPPED(ep, observer)
    COUNT["placed by make_room"] += sum(o.id not in ep.failed for o in left)
    return done


R.make_room = make_room

if __name__ == "__main__":
    plans = diagnosis_plans("dense", 20)
    for name in ("plan2place", "dfs"):
        solver = get_solver(name)
        out = sum(len(solver.solve(p, seed=s).unplaced) for p in plans for s in (0, 1))
        print(f"{name}: {out} of {2 * sum(len(p.objects) for p in plans)} objects left out")
    print(dict(COUNT))
