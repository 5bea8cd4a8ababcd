"""What the A/B experiments on the step-wise placers share (`app/bench/results/plan2place/*/diagnose.py`, `gate.py`):
the sets and metrics they judge, the diagnosis plans and the plans of a fresh gate, a diagnosis run, and their report
(a variant minus the placer without it, paired over the same runs, then the PTO p50s)."""

from __future__ import annotations

import json
import statistics
from pathlib import Path

import numpy as np

from app.bench.paired import alternating, cell, header, interval, paired, variant_rows
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans

SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
METRICS = (("cnt", 100, True, 2), ("key_nav", 100, True, 2), ("constraint_satisfaction", 100, True, 2),
           ("energy", 1, False, 3), ("realism", 100, True, 2), ("pto_ms", 1, False, 2))


def diagnosis_plans(ds: str, n: int) -> list:
    """`n` plans of set `ds` off the placement bench's sample (`i % step == step // 2`; the `seen` validation split),
    on which the experiments look before writing their rules."""
    recs = load_dataset(ds, "validation" if ds == "seen" else None)
    step = max(len(recs) // 20, 1)
    return [r.plan for i, r in enumerate(recs) if i % step == step // 2][:n]


def human_rooms() -> list:
    """The iTHOR rooms have no fresh recipe: 24 off the placement bench's sample (index % 6 == 0), the diagnosis plans
    (3) and the grid critic's gate (1, 4)."""
    return [r.plan for i, r in enumerate(load_dataset("human")) if i % 6 in (2, 5)][:24]


def finish_runs(ds: str, small: bool = True) -> list[tuple]:
    """The placement bench's stored Plan2Place runs of set `ds` in which the exact finish may run (every object
    placed, from `MIN_MET` to 99 % of the constraints met) in a small room (at most `MAX_OBJECTS` objects) or, with
    `small` false, in a larger one (where the window may): (plan, seed) pairs, for the probes that replay them."""
    from models.placement.exact_finish import MAX_OBJECTS, MIN_MET
    rows = json.loads((Path(__file__).parent / "results" / f"placement-{ds}" / "results.json").read_text())
    plans = {r.plan.id: r.plan for r in load_dataset(ds, "validation" if ds == "seen" else None)}
    return [(plans[r["plan"]], r["seed"]) for r in rows if r["solver"] == "plan2place" and not r["unplaced"]
            and (r["n_objects"] <= MAX_OBJECTS) == small and MIN_MET <= r["constraint_satisfaction"] < 1]


def fresh_sets(tag: str) -> dict:
    """A gate's plans (set -> (plans, seeds)): fresh plans of `tag`, 48 `dense` x 5 seeds and 24 per other generated
    set x 2 seeds; `human`: `human_rooms` x 2 seeds."""
    return {ds: (fresh_plans(ds, tag, 48), range(5)) if ds == "dense" else
            (human_rooms() if ds == "human" else fresh_plans(ds, tag, 24), range(2)) for ds in SETS}


def p50s(rows: list[dict], placers, variants) -> list[str]:
    """The PTO p50 per object of each set and placer, the first variant -> the second."""
    out = []
    for label in dict.fromkeys(r["set"] for r in rows):
        for placer in placers:
            p50 = [statistics.median(r["pto_ms"] for r in rows if (r["set"], r["placer"], r["solver"]) ==
                                     (label, placer, v)) for v in variants]
            out.append(f"- {label} / {placer}: {p50[0]:.2f} -> {p50[1]:.2f} ({100 * (p50[1] / p50[0] - 1):+.1f} %)")
    return out


def pooled_constraints(rows: list[dict], placer: str, variants, metric: str = "constraint_satisfaction") -> str:
    """Constraints met (or another higher-is-better `metric`) of `placer`, the second variant minus the first, over
    every set's runs pooled (each plan a unit of the bootstrap): the pooled condition of a gate's rule."""
    mine = [{**r, "plan": f"{r['set']}/{r['plan']}"} for r in rows if r["placer"] == placer]
    diffs = paired(mine, metric, *reversed(list(variants)))
    return f"- {placer}: " + cell(*(100 * v for v in interval(diffs, np.random.default_rng(0))), True)


def variant_report(name: str, plans: str, rows: list[dict], variants, placers, metrics=METRICS) -> str:
    """`name` minus the placer without it (`variants`: (without, with)) on `plans` (words), from `alternating`'s
    rows."""
    return "\n".join([f"{name} - without, {plans}, mean over the same (plan, seed) runs [95 % bootstrap interval over "
                      "plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating in one process); "
                      "**bold** = better with the interval clear of 0, _italic_ = worse.", "",
                      *header("set / placer", metrics), *variant_rows(rows, *variants, metrics, placers), "",
                      "PTO p50 per object (ms), without -> with:", "", *p50s(rows, placers, variants)]) + "\n"


def diagnose(folder: Path, name: str, where, attribute: str, variants: dict, placers, sets=SETS) -> str:
    """A change (`where.attribute` taking each of `variants`' values; the first: without it) on 20 diagnosis plans per
    set x 2 seeds, the placers alternating in one process: `diagnose.json` and `diagnose.md` written to `folder`; the
    report."""
    plan_sets = {ds: (diagnosis_plans(ds, 20), range(2)) for ds in sets}
    rows = alternating(plan_sets, where, attribute, variants, METRICS, placers)
    (folder / "diagnose.json").write_text(json.dumps(rows))
    report = variant_report(name, "diagnosis plans", rows, tuple(variants), placers)
    (folder / "diagnose.md").write_text(report)
    return report
