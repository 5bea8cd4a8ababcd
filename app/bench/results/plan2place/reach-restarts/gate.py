"""decision.md's gate: Plan2Place with the restarts also where every object is placed but a task object is out of
reach and without, on fresh plans of tag `reach-restarts`, alternating in one process; writes `runs.json` and
`result.md` here, the rule's pooled Key_NAV figure last. The variant is `restarts-reach/diagnose.py`'s `reach_too`
(an earlier look at the same rule on the diagnosis plans; in the tree this gate ran on, 026ffe3, it was the flag
`restarts.FOR_REACH`, removed when the gate failed):

    PYTHONPATH=. python app/bench/results/plan2place/reach-restarts/gate.py
"""
import importlib.util
from pathlib import Path

from app.bench.gates import METRICS, SETS, human_rooms, pooled_constraints, variant_report
from app.bench.paired import alternating, store
from models.datasets.fresh import fresh_plans
from models.placement import restarts

HERE = Path(__file__).parent
PLACERS = ("plan2place",)


def reach_too():
    """The earlier diagnosis's variant of `restarts.restarted` (its script is not a package module)."""
    spec = importlib.util.spec_from_file_location("restarts_reach", HERE.parent / "restarts-reach" / "diagnose.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.reach_too


def plan_sets() -> dict:
    """set -> (plans, seeds), as decision.md says."""
    sizes = {"unseen_a": (96, range(2)), "dense": (48, range(5)), "seen": (48, range(1)), "unseen_b": (48, range(1))}
    return {ds: (human_rooms(), range(2)) if ds == "human" else (fresh_plans(ds, "reach-restarts", sizes[ds][0]),
                                                                 sizes[ds][1]) for ds in SETS}


if __name__ == "__main__":
    variants = {"without": restarts.restarted, "for reach": reach_too()}
    runs = alternating(plan_sets(), restarts, "restarted", variants, METRICS, PLACERS)
    report = variant_report("Restarts where a task object is out of reach", "fresh plans", runs, tuple(variants),
                            PLACERS)
    store(HERE, runs, report + "\nKey_NAV (x 100), with minus without, the five sets pooled:\n\n"
          + pooled_constraints(runs, "plan2place", variants, "key_nav") + "\n")
