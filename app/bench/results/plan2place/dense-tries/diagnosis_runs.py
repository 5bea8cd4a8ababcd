"""Plan2Place on the diagnosis plans of a set (`i % step == step // 2`, `step = len // 20`), 2 seeds, as the tries
in this folder run it: their summary line (CNT, constraints, Key_NAV x 100, energy, median ms per object) and the
rows, saved to `save` (.npy) for pairing two runs."""
import time

import numpy as np

from app.bench.placement import score
from models.datasets import load_dataset
from models.placement.base import get_solver


def run(ds: str, n: int, label: str, save: str) -> str:
    recs = load_dataset(ds, "validation" if ds == "seen" else None)
    step = max(len(recs) // 20, 1)
    solver, rows = get_solver("plan2place"), []
    for r in [r for i, r in enumerate(recs) if i % step == step // 2][:n]:
        for seed in (0, 1):
            t = time.perf_counter()
            layout = solver.solve(r.plan, seed=seed)
            s = score(r.plan, layout)
            assert s["collisions"] == 0
            rows.append((s["cnt"], s["constraint_satisfaction"], s["key_nav"], s["energy"],
                         (time.perf_counter() - t) / len(r.plan.objects)))
    a = np.array(rows)
    np.save(save, a)
    return "%s %s cnt %.2f cons %.2f keynav %.2f energy %.3f ms/obj %.2f" % (
        label, ds, 100 * a[:, 0].mean(), 100 * a[:, 1].mean(), 100 * a[:, 2].mean(), a[:, 3].mean(),
        1000 * np.median(a[:, 4]))
