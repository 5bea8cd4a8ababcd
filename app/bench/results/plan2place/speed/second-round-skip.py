"""The second polish round passes over an object tried before with nothing moved since: does any layout change? The
fresh `dense` plans of `second-round/` (48 x seeds 0-4, Plan2Place and greedy), solved by the code as it is, against
the layouts `second-round/runs.json` stored for two full rounds; and the time per object of both.

    PYTHONPATH=. python app/bench/results/plan2place/speed/second-round-skip.py   # -> second-round-skip.txt
"""
import json
import time
from pathlib import Path

import numpy as np

from app.bench.paired import fingerprint
from models.datasets.fresh import fresh_plans
from models.placement.base import get_solver

HERE = Path(__file__).parent
stored = {(r["placer"], r["plan"], r["seed"]): r for r in json.loads((HERE.parent / "second-round" / "runs.json").read_text())
          if r["set"] == "dense (fresh)" and r["solver"] == "two in crowded rooms"}
same, ms = 0, {"now": [], "stored": []}
for name in ("plan2place", "greedy"):
    solver = get_solver(name)
    for plan in fresh_plans("dense", "second-round", 48):
        for seed in range(5):
            t = time.perf_counter()
            layout = solver.solve(plan, seed=seed)
            old = stored[(name, plan.id, seed)]
            same += fingerprint(layout) == old["layout"]
            if name == "plan2place":
                ms["now"].append(1000 * (time.perf_counter() - t) / len(plan.objects))
                ms["stored"].append(old["pto_ms"])
text = (f"{same} of {len(stored)} layouts equal to the stored two full rounds; Plan2Place p50 {np.median(ms['now']):.2f} "
        f"ms per object now, {np.median(ms['stored']):.2f} stored (another process, alternating with one round)\n")
(HERE / "second-round-skip.txt").write_text(text)
print(text)
