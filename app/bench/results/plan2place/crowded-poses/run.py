"""Three make-way poses in crowded rooms (the variant) against one (the code as it is), Plan2Place and greedy, on
the plans `decision.md` names, alternating plan by plan in one process; writes `runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/crowded-poses/run.py

It ran on the code of dd15cd2 (decision.md's commit): the change it decided removed `MAKE_WAY_POSES_CROWDED`, which
this script sets, so re-run it in a worktree of dd15cd2. It then stored every field of `score` and the poses; `runs.json`
keeps the fields below and a hash of the poses (the report made from it is the same, checked).
"""
import hashlib
import json
import sys
import time
from pathlib import Path

import numpy as np

import models.placement.polish as polish
from app.bench.paired import cell, header, interval, paired
from app.bench.placement import score
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans
from models.placement.base import get_solver

HERE = Path(__file__).parent
TAG, N_DENSE = "crowded-poses", 48
METRICS = (("constraint_satisfaction", 100, True, 2), ("cnt", 100, True, 2), ("key_nav", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3), ("pto_s", 1000, False, 2))
VARIANTS = {"one pose": 1, "three poses": polish.MAKE_WAY_POSES}


def plan_sets() -> dict[str, tuple[list, range]]:
    human = [r.plan for r in load_dataset("human") if polish.crowded(r.plan)]
    others = {ds: [r.plan for i, r in enumerate(load_dataset(ds, "validation" if ds == "seen" else None)) if i % 25 == 7][:8]
              for ds in ("seen", "unseen_a")}
    return {"dense (fresh)": (fresh_plans("dense", TAG, N_DENSE), range(5)), "human (crowded)": (human, range(5)),
            **{f"{ds} (identity check)": (plans, range(2)) for ds, plans in others.items()}}


def fingerprint(layout) -> str:
    """A short hash of the poses: enough to tell whether two layouts are the same."""
    poses = sorted((p.id, p.x, p.z, p.rotation) for p in layout.placements)
    return hashlib.sha1(repr(poses).encode()).hexdigest()[:12]


def run() -> list[dict]:
    rows = []
    for label, (plans, seeds) in plan_sets().items():
        print(label, len(plans), "plans", file=sys.stderr)
        for name in ("plan2place", "greedy"):
            solver = get_solver(name)
            for plan in plans:
                for seed in seeds:
                    for variant, poses in VARIANTS.items():
                        polish.MAKE_WAY_POSES_CROWDED = poses
                        t = time.perf_counter()
                        layout = solver.solve(plan, seed=seed)
                        dt = time.perf_counter() - t
                        scored = score(plan, layout)
                        rows.append({**{m: scored.get(m) for m, *_ in METRICS if m != "pto_s"},
                                     "pto_s": dt / len(plan.objects), "set": label,
                                     "placer": name, "solver": variant, "plan": plan.id, "seed": seed,
                                     "layout": fingerprint(layout)})
    polish.MAKE_WAY_POSES_CROWDED = VARIANTS["one pose"]
    return rows


def report(rows: list[dict]) -> str:
    rng = np.random.default_rng(0)
    lines = ["Three poses - one pose per make-way move in crowded rooms, mean over the same (plan, seed) runs "
             "[95 % bootstrap interval over plans]; metrics x 100, energy as is, PTO in ms per object (two "
             "variants alternating in one process); **bold** = better with the interval clear of 0, _italic_ = worse.",
             "", *header("set / placer", METRICS)]
    for label in dict.fromkeys(r["set"] for r in rows):
        for placer in ("plan2place", "greedy"):
            mine = [r for r in rows if r["set"] == label and r["placer"] == placer]
            cells = [cell(*(sc * v for v in interval(paired(mine, m, "three poses", "one pose"), rng)), up, d)
                     for m, sc, up, d in METRICS]
            same = sum(a["layout"] == b["layout"] for a, b in zip(mine[::2], mine[1::2]))
            lines.append(f"| {label} / {placer} ({len(mine) // 2} runs, {same} layouts unchanged) | "
                         + " | ".join(cells) + " |")
    for label in dict.fromkeys(r["set"] for r in rows):
        mine = [r for r in rows if r["set"] == label and r["placer"] == "plan2place"]
        p50 = {v: 1000 * float(np.median([r["pto_s"] for r in mine if r["solver"] == v])) for v in VARIANTS}
        lines.append(f"\n{label}, Plan2Place PTO p50: " + ", ".join(f"{v} {ms:.2f} ms" for v, ms in p50.items()))
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    runs = run()
    (HERE / "runs.json").write_text(json.dumps(runs))
    (HERE / "result.md").write_text(report(runs))
    print(report(runs))
