"""The variant as gated: in the reach-kept solve (models.placement.reach_kept, as it was before), when its steps leave
objects out for reach (`WALLS`), solve once more keeping reach with those objects placed first; the third episode
replaces the second if it leaves no more task objects out of reach at a lower energy. Then the module's rule against
the first episode. `walls_first` is what shipped (reach_kept.solve_keeping now); `walls_first_when_kept` the cheaper
form of `diagnose-when-kept.md`."""
import dataclasses

from models.placement.polish import Standing
from models.placement.reach_kept import AGAIN, WALLS, better, out_of_reach


def _solved(again, repair, first):
    steps = []
    ep = again(first, steps.append)
    repair(ep, steps.append)
    return ep, steps


def _walls_placed_first(new, steps, again, repair):
    """(`new`, its steps), or the episode with `new`'s objects left out for reach placed first if it is better."""
    if walls := [oid for oid, why in new.failed.items() if why == WALLS]:
        third, third_steps = _solved(again, repair, walls)
        if out_of_reach(third) <= out_of_reach(new) and Standing(third).energy < Standing(new).energy:
            return third, third_steps
    return new, steps


def _kept(ep, new, steps, observer):
    if not better(new, ep):
        return ep
    for k, step in enumerate(steps if observer is not None else ()):
        observer(dataclasses.replace(step, why=f"{AGAIN}; {step.why}" if step.why else AGAIN, restart=k == 0))
    return new


def walls_first(ep, repair, again, observer=None):
    if not out_of_reach(ep):
        return ep
    return _kept(ep, *_walls_placed_first(*_solved(again, repair, []), again, repair), observer)


def walls_first_when_kept(ep, repair, again, observer=None):
    """The same, but the third solve is tried only where the second one is kept (fewer solves: the p50's cost)."""
    if not out_of_reach(ep):
        return ep
    new, steps = _solved(again, repair, [])
    if not better(new, ep):
        return ep
    return _kept(ep, *_walls_placed_first(new, steps, again, repair), observer)
