"""Does training save time? The shipped network, the same network untrained and greedy, all with the repairs, timed
alone in one process taking turns plan by plan (app.bench.plan2place.speed), on each set's bench plans x 3 seeds.
A network that leaves fewer constraints broken after its steps sends fewer rooms to the second solve and the
repairs, so its time per object is part of what training changes. Writes runs-<set>.json (CPU ms per object per
plan and seed) and, from those, time.md (p50 and the paired ratio of CPU time per run, geometric mean with a 95 %
bootstrap interval over plans):
PYTHONPATH=. python app/bench/results/plan2place/learning/time/run.py [--table-only]"""

import json
import sys
from pathlib import Path

import numpy as np

from app.bench.paired import interval, paired
from app.bench.placement import pick_records
from app.bench.plan2place import speed

HERE = Path(__file__).parent
SETS = {"seen": 100, "unseen_a": 100, "unseen_b": 100, "dense": 100, "human": 120}
SEEDS = 3
TRAINED, UNTRAINED, GREEDY = "plan2place", "plan2place_untrained", "greedy"


def run(dataset: str, n: int) -> list[dict]:
    res = speed(dataset, n, SEEDS, [GREEDY, TRAINED, UNTRAINED])
    ids = [r.plan.id for r in pick_records(dataset, n)]
    keys = [(plan, seed) for seed in range(SEEDS) for plan in ids]
    return [{"solver": name, "plan": plan, "seed": seed, "log_cpu": float(np.log(cpu)), "cpu_ms": 1000 * cpu}
            for name, r in res.items() for (plan, seed), cpu in zip(keys, r["cpu"], strict=True)]


def ratio(rows: list[dict], a: str, b: str, rng) -> str:
    mean, lo, hi = interval(paired(rows, "log_cpu", a, b), rng)
    text = f"{np.exp(mean):.2f} [{np.exp(lo):.2f}, {np.exp(hi):.2f}]"
    return f"**{text}**" if hi < 0 else f"_{text}_" if lo > 0 else text


def table() -> str:
    rng = np.random.default_rng(0)
    lines = [__doc__.split("\n\n")[0].replace("\n", " "), "",
             "CPU ms per object; ratios of the shipped network's time to the other's, run by run (**bold**: clearly "
             "faster, _italic_: clearly slower).", "",
             "| set (plans x seeds) | greedy p50 | shipped p50 | untrained p50 | shipped / untrained | shipped / greedy |",
             "| --- | --- | --- | --- | --- | --- |"]
    for s, n in SETS.items():
        path = HERE / f"runs-{s}.json"
        if not path.exists():
            continue
        rows = json.loads(path.read_text())
        p50 = {name: np.median([r["cpu_ms"] for r in rows if r["solver"] == name]) for name in (GREEDY, TRAINED, UNTRAINED)}
        lines.append(f"| `{s}` ({n} x {SEEDS}) | {p50[GREEDY]:.1f} | {p50[TRAINED]:.1f} | {p50[UNTRAINED]:.1f} | "
                     f"{ratio(rows, TRAINED, UNTRAINED, rng)} | {ratio(rows, TRAINED, GREEDY, rng)} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    if "--table-only" not in sys.argv:
        for s, n in SETS.items():
            (HERE / f"runs-{s}.json").write_text(json.dumps(run(s, n)))
            print(s, "done", flush=True)
    (HERE / "time.md").write_text(text := table())
    print(text)
