"""Why Plan2Place leaves constraints unmet in the iTHOR rooms (`human`), where Z3 meets nearly all: on the 16
diagnosis plans x 2 seeds, each unmet constraint of a placed object is put in one class, by what the polish would
need: "a legal pose meets more" (the polish refused it: energy over the allowance, or reach), "only an occupied pose
meets more" (a make-way move, not found or refused), "no pose anywhere meets more" (alone, the object cannot meet
more: a trade between its constraints, or several objects would have to move); objects left out are counted apart.

    PYTHONPATH=. python app/bench/results/plan2place/unmet-human-why.py > unmet-human-why.txt
"""
import sys
from collections import Counter
from pathlib import Path

from models.placement.base import get_solver
from models.placement.greedy import Episode
from models.placement.moves import legal_poses
from models.placement.polish import _involved, met, met_among

sys.path.insert(0, str(Path(__file__).parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402


def main() -> Counter:
    solver, why = get_solver("plan2place"), Counter()
    for plan in diagnosis_plans("human", 16):
        for seed in (0, 1):
            layout = solver.solve(plan, seed=seed)
            fixed = {p.id: (p.x, p.z, p.rotation) for p in layout.placements}
            why["object left out"] += sum(o.id not in fixed for o in plan.objects)
            ep = Episode(plan, fixed)  # the layout, every object fixed where Plan2Place put it
            ep.finish_greedily()
            for p in ep.placed:
                others = [q for q in ep.placed if q is not p]
                now = met_among(ep, ep.placed, {p.id})
                missing = _involved(ep, p.id, others) - now
                if missing <= 0:
                    continue
                obj = ep.problem.plan.object(p.id)
                count = met(ep, p.id, None, others)
                legal = legal_poses(ep, obj, others, ep.scorer.bodies(obj)[0], ep.scorer.swept(obj), relax=False)
                if count.max() <= now:
                    why["no pose anywhere meets more"] += missing
                elif len(legal) and count[legal].max() > now:
                    why["a legal pose meets more"] += missing
                else:
                    why["only an occupied pose meets more"] += missing
    return why


if __name__ == "__main__":
    counts = main()
    print("unmet constraints of Plan2Place on 16 `human` diagnosis plans x 2 seeds, by what would meet them:")
    for k, v in counts.most_common():
        print(f"  {k}: {v}")
