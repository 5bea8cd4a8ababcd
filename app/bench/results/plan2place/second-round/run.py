"""A second polish round in crowded rooms (the variant) against one round, Plan2Place and greedy, on the plans
`decision.md` names, the order alternating from run to run in one process; writes `runs.json` and `result.md` here.

    PYTHONPATH=. python app/bench/results/plan2place/second-round/run.py

It ran on the code before the change it decided (one round everywhere); `polish` now runs the second round itself,
so re-run it in a worktree of that commit (the one that added this script).
"""
import hashlib
import json
import sys
import time
from pathlib import Path

import numpy as np

import models.placement.repair as repair
from app.bench.paired import cell, header, interval, paired
from app.bench.placement import score
from models.datasets import load_dataset
from models.datasets.fresh import fresh_plans
from models.placement.base import get_solver
from models.placement.habits import crowded
from models.placement.polish import polish

HERE = Path(__file__).parent
TAG = "second-round"
METRICS = (("constraint_satisfaction", 100, True, 2), ("cnt", 100, True, 2), ("key_nav", 100, True, 2),
           ("realism", 100, True, 2), ("energy", 1, False, 3), ("pto_ms", 1, False, 2))


def two_rounds(ep, observer=None):
    moved = polish(ep, observer)
    return moved + (polish(ep, observer) if moved and crowded(ep.problem.plan) else [])


VARIANTS = {"one round": polish, "two in crowded rooms": two_rounds}


def plan_sets() -> dict[str, tuple[list, range]]:
    human = [r.plan for r in load_dataset("human") if crowded(r.plan)]
    others = {ds: [r.plan for i, r in enumerate(load_dataset(ds, "validation" if ds == "seen" else None))
                   if i % 25 == 11][:8] for ds in ("seen", "unseen_a")}
    return {"dense (fresh)": (fresh_plans("dense", TAG, 48), range(5)), "human (crowded)": (human, range(5)),
            **{f"{ds} (identity check)": (plans, range(2)) for ds, plans in others.items()}}


def fingerprint(layout) -> str:
    return hashlib.sha1(repr(sorted((p.id, p.x, p.z, p.rotation) for p in layout.placements)).encode()).hexdigest()[:12]


def run() -> list[dict]:
    rows, k, shipped = [], 0, repair.polish
    for label, (plans, seeds) in plan_sets().items():
        print(label, len(plans), "plans", file=sys.stderr, flush=True)
        for name in ("plan2place", "greedy"):
            solver = get_solver(name)
            for plan in plans:
                for seed in seeds:
                    k += 1
                    for variant in list(VARIANTS)[::1 if k % 2 else -1]:
                        repair.polish = VARIANTS[variant]
                        t = time.perf_counter()
                        layout = solver.solve(plan, seed=seed)
                        ms = 1000 * (time.perf_counter() - t) / len(plan.objects)
                        got = score(plan, layout)
                        rows.append({**{m: got.get(m) for m, *_ in METRICS if m != "pto_ms"}, "pto_ms": ms,
                                     "set": label, "placer": name, "solver": variant, "plan": plan.id, "seed": seed,
                                     "layout": fingerprint(layout)})
    repair.polish = shipped
    return rows


def report(rows: list[dict]) -> str:
    rng = np.random.default_rng(0)
    old, new = VARIANTS
    lines = [f"{old} -> {new}: the difference, mean over the same (plan, seed) runs [95 % bootstrap interval over "
             "plans]; metrics x 100, energy as is, PTO in ms per object (the two alternating in one process); "
             "**bold** = better with the interval clear of 0, _italic_ = worse.", "", *header("set / placer", METRICS)]
    for label in dict.fromkeys(r["set"] for r in rows):
        for placer in ("plan2place", "greedy"):
            mine = [r for r in rows if r["set"] == label and r["placer"] == placer]
            layouts = {(r["plan"], r["seed"], r["solver"]): r["layout"] for r in mine}
            same = sum(layouts[(p, s, new)] == layouts[(p, s, old)] for p, s, v in layouts if v == old)
            cells = [cell(*(sc * v for v in interval(paired(mine, m, new, old), rng)), up, d) for m, sc, up, d in METRICS]
            lines.append(f"| {label} / {placer} ({len(mine) // 2} runs, {same} layouts unchanged) | "
                         + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main() -> None:
    rows = run()
    text = report(rows)
    for name, body in (("runs.json", json.dumps(rows)), ("result.md", text)):
        (HERE / name).write_text(body)
    print(text)


if __name__ == "__main__":
    main()
