"""Solving again from another random state (models.placement.restarts) also where nothing is left out but a task
object is out of the robot's reach, kept by the same rule (no fewer placed, no more out of reach, a lower energy),
against the shipped restarts (only where an object is left out), on the diagnosis plans (20 per set x 2 seeds; never
the bench's or fresh plans), Plan2Place and greedy alternating in one process; writes `diagnose.md` and
`diagnose.json` here:

    PYTHONPATH=. python app/bench/results/plan2place/restarts-reach/diagnose.py [SET ...]
"""
import dataclasses
import sys
from pathlib import Path

from app.bench.gates import SETS, diagnose
from models.placement import restarts
from models.placement.reach_kept import out_of_reach


def reach_too(ep, again, observer=None):
    """`restarts.restarted`, running while an object is left out or a task object is out of reach."""
    for salt in range(1, restarts.RESTARTS + 1):
        if not ep.failed and not out_of_reach(ep):
            break
        steps = []
        new = again(salt, steps.append)
        if restarts.better(new, ep):
            ep = new
            for k, step in enumerate(steps if observer is not None else ()):
                observer(dataclasses.replace(step, why=f"{restarts.AGAIN}; {step.why}" if step.why else
                                             restarts.AGAIN, restart=k == 0))
    return ep


if __name__ == "__main__":
    print(diagnose(Path(__file__).parent, "restarts where a task object is out of reach too", restarts, "restarted",
                   {"left_out": restarts.restarted, "reach_too": reach_too}, ("plan2place", "greedy"),
                   sys.argv[1:] or SETS))
