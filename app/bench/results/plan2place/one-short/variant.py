"""Plan2Place solving the plan once more from where its random state has got to, like `second-try/`, but only when its
layout is one constraint short of all: in place of `models.placement.plan2place.solver.place`. The second layout is
kept by the second solve's rule (models.placement.reorder.better)."""
from models.placement.plan2place import solver
from models.placement.reorder import better, met

SHIPPED = solver.place


def one_short(ep) -> bool:
    """Exactly one of the plan's constraints (globals and relations, as the metric counts them) is not met."""
    total = sum(1 + len(oc.relations) for oc in ep.problem.constraints.objects.values())
    return total - met(ep) == 1


def place_once_more(policy, plan, rng, use_global=True, fixed=None, observer=None, repair=True, guard=True,
                    keep_reach=True):
    ep = SHIPPED(policy, plan, rng, use_global, fixed, observer, repair, guard, keep_reach)
    if repair and one_short(ep):
        again = SHIPPED(policy, plan, rng, use_global, fixed, None, repair, guard, keep_reach)
        if better(again, ep):
            ep = again
    return ep
