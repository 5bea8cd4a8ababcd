"""The variant: in the reach-kept solve (models.placement.reach_kept), when its steps leave objects out for reach
(`WALLS`), solve once more keeping reach with those objects placed first; the third episode replaces the second if
it leaves no more task objects out of reach at a lower energy. Then the module's rule against the first episode."""
import dataclasses

from models.placement.polish import Standing
from models.placement.reach_kept import AGAIN, WALLS, better, out_of_reach


def walls_first(ep, repair, again, observer=None):
    if not out_of_reach(ep):
        return ep
    steps = []
    new = again([], steps.append)
    repair(new, steps.append)
    if walls := [oid for oid, why in new.failed.items() if why == WALLS]:
        third_steps = []
        third = again(walls, third_steps.append)
        repair(third, third_steps.append)
        if out_of_reach(third) <= out_of_reach(new) and Standing(third).energy < Standing(new).energy:
            new, steps = third, third_steps
    if not better(new, ep):
        return ep
    for k, step in enumerate(steps if observer is not None else ()):
        observer(dataclasses.replace(step, why=f"{AGAIN}; {step.why}" if step.why else AGAIN, restart=k == 0))
    return new


def walls_first_when_kept(ep, repair, again, observer=None):
    """The same, but the third solve is tried only where the second one is kept (fewer solves: the p50's cost)."""
    if not out_of_reach(ep):
        return ep
    steps = []
    new = again([], steps.append)
    repair(new, steps.append)
    if not better(new, ep):
        return ep
    if walls := [oid for oid, why in new.failed.items() if why == WALLS]:
        third_steps = []
        third = again(walls, third_steps.append)
        repair(third, third_steps.append)
        if out_of_reach(third) <= out_of_reach(new) and Standing(third).energy < Standing(new).energy:
            new, steps = third, third_steps
    for k, step in enumerate(steps if observer is not None else ()):
        observer(dataclasses.replace(step, why=f"{AGAIN}; {step.why}" if step.why else AGAIN, restart=k == 0))
    return new
