"""Z3 stating its model through the Python API (smt.py at BEFORE, read from git) against reading it as SMT-LIB text
(now), alternating in one process, on rooms of the placement bench's sample where Z3 used its whole budget in the
stored run before (`unseen_a`: all 22, `dense`: 20 evenly spaced; seeds 0 and 1); the bench's own re-run of Z3 mixes
the encoding with the machine's state, and there Z3 works to the clock. Writes ab-<set>.jsonl (one line per run) and
ab-<set>.md:

    PYTHONPATH=. python app/bench/results/plan2place/z3-smtlib/ab.py unseen_a            # the runs, then the summary
    PYTHONPATH=. python app/bench/results/plan2place/z3-smtlib/ab.py dense --summary     # the summary of stored runs
"""
import importlib.util
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from app.bench.placement import pick_records, score
from models.placement import smt as new

HERE = Path(__file__).parent
BEFORE = "993808a"
ROOMS = {"unseen_a": 22, "dense": 20}
METRICS = (("cs", "constraints met", 1), ("cnt", "CNT", 1), ("e", "energy", -1), ("kn", "Key_NAV", 1),
           ("re", "realism", 1), ("t", "seconds per room", -1))  # (key, label, +1 where higher is better)


def smt_before():
    """smt.py as it was at BEFORE, loaded as a module of its own."""
    text = subprocess.run(["git", "show", f"{BEFORE}:models/placement/smt.py"], capture_output=True, text=True,
                          check=True, cwd=HERE).stdout
    path = Path(tempfile.mkdtemp()) / "smt_before.py"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location("smt_before", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def hard_rooms(dataset: str) -> list[str]:
    """`ROOMS[dataset]` rooms, evenly spaced, of those where the stored Z3 run before used at least 95 % of its budget
    (0.5 s per object)."""
    path = f"app/bench/results/placement-{dataset}/results.json"
    rows = json.loads(subprocess.run(["git", "show", f"{BEFORE}:{path}"], capture_output=True, text=True, check=True,
                                     cwd=HERE).stdout)
    hard = sorted({r["plan"] for r in rows if r["solver"] == "z3" and r["time_s"] >= 0.95 * 0.5 * r["n_objects"]})
    step = max(len(hard) // ROOMS[dataset], 1)
    return hard[::step][:ROOMS[dataset]]


def run(dataset: str) -> None:
    old, plans = smt_before(), {r.plan.id: r.plan for r in pick_records(dataset, 100)}
    with (HERE / f"ab-{dataset}.jsonl").open("w") as out:
        for k, pid in enumerate(hard_rooms(dataset)):
            p = plans[pid]
            for s in (0, 1):
                row = {"plan": pid, "n": len(p.objects), "seed": s}
                for name, mod in (("old", old), ("new", new))[::1 if (k + s) % 2 == 0 else -1]:
                    t = time.perf_counter()
                    layout = mod.Z3Solver().solve(p, s)
                    m = score(p, layout)
                    row[name] = {"cs": m["constraint_satisfaction"], "cnt": m["cnt"], "e": m["energy"],
                                 "kn": m["key_nav"], "re": m["realism"], "t": round(time.perf_counter() - t, 2)}
                out.write(json.dumps(row) + "\n")
                out.flush()


def summary(dataset: str) -> str:
    rows = [json.loads(line) for line in (HERE / f"ab-{dataset}.jsonl").read_text().splitlines()]
    rng = np.random.default_rng(0)
    lines = ["Z3 reading SMT-LIB text minus Z3 stated through the Python API, alternating in one process, on the "
             f"{len({r['plan'] for r in rows})} `{dataset}` rooms where Z3 used its whole budget before ({len(rows)} "
             "runs); mean [95 % bootstrap interval over rooms]; runs better / worse.", "",
             "| metric | API | SMT-LIB text | text - API | better / worse |", "| --- | --- | --- | --- | --- |"]
    for key, label, up in METRICS:
        ok = [r for r in rows if r["new"][key] is not None and r["old"][key] is not None]
        per = {}
        for r in ok:
            per.setdefault(r["plan"], []).append(r["new"][key] - r["old"][key])
        groups = list(per.values())
        boot = [statistics.fmean(x for i in rng.integers(len(groups), size=len(groups)) for x in groups[i])
                for _ in range(2000)]
        d = [x for g in groups for x in g]
        lines.append(f"| {label} ({len(d)}) | {statistics.fmean(r['old'][key] for r in ok):.3f} | "
                     f"{statistics.fmean(r['new'][key] for r in ok):.3f} | {statistics.fmean(d):+.3f} "
                     f"[{np.percentile(boot, 2.5):+.3f}, {np.percentile(boot, 97.5):+.3f}] | "
                     f"{sum(up * x > 1e-9 for x in d)} / {sum(up * x < -1e-9 for x in d)} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    name = sys.argv[1]
    if "--summary" not in sys.argv:
        run(name)
    text = summary(name)
    (HERE / f"ab-{name}.md").write_text(text)
    print(text)
