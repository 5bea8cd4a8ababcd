"""decision.md's gate: Plan2Place with the restarts also where every object is placed but a task object is out of
reach (`for_reach`, this script's variant of `restarts.restarted`; it failed and was not shipped) and without, on fresh
plans of tag `reach-restarts`, alternating in one process; writes `runs.json` and `result.md` here, the rule's pooled
Key_NAV figure last:

    PYTHONPATH=. python app/bench/results/plan2place/reach-restarts/gate.py
"""
from pathlib import Path

import numpy as np

from app.bench.gates import METRICS, SETS, human_rooms, variant_report
from app.bench.paired import alternating, cell, interval, paired, store
from models.datasets.fresh import fresh_plans
from models.placement import restarts
from models.placement.reach_kept import out_of_reach

HERE = Path(__file__).parent
SHIPPED = restarts.restarted


def for_reach(ep, again, observer=None):
    """`restarts.restarted`, but solving again also while every object is placed and a task object is out of reach
    (the gate's variant, `FOR_REACH` in the tree it was gated on, 026ffe3)."""
    for salt in range(1, restarts.RESTARTS + 1):
        if not ep.failed and not out_of_reach(ep):
            break
        steps = []
        new = again(salt, steps.append)
        if restarts.better(new, ep):
            ep = new
    return ep


VARIANTS = {"without": SHIPPED, "for reach": for_reach}
PLACERS = ("plan2place",)


def plan_sets() -> dict:
    """set -> (plans, seeds), as decision.md says."""
    sizes = {"unseen_a": (96, range(2)), "dense": (48, range(5)), "seen": (48, range(1)), "unseen_b": (48, range(1))}
    return {ds: (human_rooms(), range(2)) if ds == "human" else (fresh_plans(ds, "reach-restarts", sizes[ds][0]),
                                                                 sizes[ds][1]) for ds in SETS}


def pooled_key_nav(rows: list[dict]) -> str:
    """Key_NAV, with minus without, every set's runs pooled (each plan a unit of the bootstrap)."""
    mine = [{**r, "plan": f"{r['set']}/{r['plan']}"} for r in rows if r["key_nav"] is not None]
    diffs = paired(mine, "key_nav", *reversed(list(VARIANTS)))
    return cell(*(100 * v for v in interval(diffs, np.random.default_rng(0))), True)


if __name__ == "__main__":
    runs = alternating(plan_sets(), restarts, "restarted", VARIANTS, METRICS, PLACERS)
    report = variant_report("Restarts where a task object is out of reach", "fresh plans", runs, tuple(VARIANTS),
                            PLACERS)
    store(HERE, runs, report + f"\nKey_NAV (x 100), with minus without, the five sets pooled: {pooled_key_nav(runs)}\n")
