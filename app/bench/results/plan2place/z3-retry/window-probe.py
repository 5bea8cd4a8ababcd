"""A lead, nothing changed: would Z3's window in a larger room (models.placement.window) gain from other seeds, as the
small rooms' finish did? Replays Plan2Place on the placement bench's stored runs of more than 9 objects, every object
placed, 60-99 % of the constraints met; where the window is asked and keeps nothing, asks it again from up to 2 other
seeds (drawn from the window's), noting which is kept and the seconds they took. The placer is unchanged.
window-probe.txt is of the bench's runs stored at 534802d (after the small rooms' retries shipped).
PYTHONPATH=. python app/bench/results/plan2place/z3-retry/window-probe.py  (writes window-probe.txt beside it)"""

import time
from collections import Counter
from pathlib import Path

import numpy as np

from app.bench.gates import finish_runs
from models.placement import exact_finish, window
from models.placement.base import get_solver

HERE = Path(__file__).parent
SETS, RETRIES = ("seen", "unseen_a", "human"), 2  # (`unseen_b`, `dense`: the window never acted in their gate runs)
ask = window.one_more
asked: list[tuple[str, int, float]] = []  # set, the retry kept (0: none, -1: the first ask was kept), seconds


def watched(ep, seed, work, stall_s):
    out = ask(ep, seed, work, stall_s)
    kept, start = -1, time.perf_counter()
    if out is ep:
        seeds = np.random.default_rng(seed).integers(2**31, size=RETRIES)
        kept = next((k for k, s in enumerate(seeds, 1) if ask(ep, int(s), work, stall_s) is not ep), 0)
    asked.append((current, kept, time.perf_counter() - start))
    return out


exact_finish.one_more = watched
lines = ["set: runs replayed / windows asked / kept at the first ask / kept at retry 1, 2 / seconds of the retries "
         "(median, most)"]
for current in SETS:
    runs = finish_runs(current, small=False)
    for plan, seed in runs:
        get_solver("plan2place").solve(plan, seed=seed)
    mine = [a for a in asked if a[0] == current]
    kept, secs = Counter(a[1] for a in mine), sorted(a[2] for a in mine if a[1] != -1) or [0.0]
    lines.append(f"{current}: {len(runs)} / {len(mine)} / {kept[-1]} / {kept[1]}, {kept[2]} / "
                 f"{secs[len(secs) // 2]:.2f}, {secs[-1]:.2f}")
(HERE / "window-probe.txt").write_text("\n".join(lines) + "\n")
print("\n".join(lines))
