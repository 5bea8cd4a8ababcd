"""Plan2Place solving the plan once more from where its random state has got to (fresh candidate subsets for the
policy) when its layout leaves a constraint broken; the second layout is kept by the second solve's rule
(models.placement.reorder.better). In place of `models.placement.plan2place.solver.place`."""
from models.placement.plan2place import solver
from models.placement.polish import broken
from models.placement.reorder import better

SHIPPED = solver.place


def place_twice(policy, plan, rng, use_global=True, fixed=None, observer=None, repair=True, guard=True,
                keep_reach=True):
    ep = SHIPPED(policy, plan, rng, use_global, fixed, observer, repair, guard, keep_reach)
    if repair and broken(ep):
        again = SHIPPED(policy, plan, rng, use_global, fixed, None, repair, guard, keep_reach)
        if better(again, ep):
            ep = again
    return ep
