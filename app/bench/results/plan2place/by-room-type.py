"""Plan2Place against the best other solver of each metric, per room type, on the placement bench's stored runs of
every set pooled (a plan is one of its set). The issue asks that room types with few examples do not break the
placer: training has as many plans of each of the nine types, but the human-made rooms behind the energy's prior
and the realism judge are iTHOR's four (kitchen, living room, bedroom, bathroom); the other five never had one.
Paired over the same (plan, seed) runs, 95 % bootstrap interval over plans (app.bench.paired). Reads
app/bench/results/placement-*/results.json, writes by-room-type.md beside this script:

    PYTHONPATH=. python app/bench/results/plan2place/by-room-type.py
"""

import json
from pathlib import Path

import numpy as np

from app.bench.paired import cell, header, interval, paired
from models.datasets import load_dataset
from models.energy.prior import ithor_scenes
from targets import RESULTS, SETS, best_other

HERE = Path(__file__).resolve().parent
METRICS = (("key_nav", 100, True, 1), ("constraint_satisfaction", 100, True, 1), ("realism", 100, True, 1),
           ("energy", 1, False, 3))


def pooled_runs() -> dict[str, list[dict]]:
    """Room type -> the stored runs of its plans, each plan named with its set."""
    by_type: dict[str, list[dict]] = {}
    for ds in SETS:
        room = {r.plan.id: r.plan.room.type for r in load_dataset(ds, "validation" if ds == "seen" else None)}
        for r in json.loads((RESULTS / f"placement-{ds}" / "results.json").read_text()):
            by_type.setdefault(room[r["plan"]], []).append({**r, "plan": f"{ds}/{r['plan']}"})
    return by_type


def main() -> str:
    rng, human_types = np.random.default_rng(0), {s["room_type"] for s in ithor_scenes()}
    lines = ["Plan2Place - the best other solver of each metric (named), per room type, the placement bench's stored "
             "runs of every set pooled; mean over the same (plan, seed) pairs [95 % bootstrap interval over plans]; "
             "metrics x 100, energy as is; **bold** = Plan2Place better with the interval clear of 0, _italic_ = "
             "worse. `iTHOR`: the type has human-made rooms behind the prior and the realism judge.", "",
             *header("room type (plans, iTHOR)", METRICS)]
    for room, rows in sorted(pooled_runs().items()):
        n = len({r["plan"] for r in rows})
        cells = []
        for metric, scale, up, digits in METRICS:
            name = best_other(rows, metric, up)
            cells.append(f"{cell(*(scale * v for v in interval(paired(rows, metric, 'plan2place', name), rng)), up, digits)}"
                         f" vs {name}")
        lines.append(f"| {room} ({n}{', iTHOR' if room in human_types else ''}) | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    text = main()
    (HERE / "by-room-type.md").write_text(text)
    print(text)
