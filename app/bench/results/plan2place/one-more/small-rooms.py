"""A lead, not built: Z3's one-more question (`smt.one_more_met`) in the small rooms where the exact finish ran and
its optimiser's layout was not kept. Replays Plan2Place on the placement bench's stored runs with at most 9 objects,
every object placed and 60-99 % of the constraints met; where the finish returns the episode unchanged, asks the
window's question (`window.one_more`) of the whole room, the fixed objects kept: any layout that keeps every met
constraint and meets one more; counts how often the judge (`reorder.better`) would keep it. The placer is unchanged.
small-rooms.txt is of the bench's runs stored at 64fa608.
PYTHONPATH=. python app/bench/results/plan2place/one-more/small-rooms.py  (writes small-rooms.txt beside it)"""

import time
from collections import Counter
from pathlib import Path

from app.bench.gates import finish_runs
from models.placement import exact_finish, smt
from models.placement.base import get_solver
from models.placement.reorder import met
from models.placement.window import one_more, window

HERE = Path(__file__).parent
SETS = ("seen", "unseen_a", "unseen_b", "dense", "human")
asked: list[tuple[str, int, bool, bool, float]] = []  # set, constraints broken, found, kept, seconds
finish, ask = exact_finish.finished_exactly, smt.one_more_met
found: list[bool] = []


def counted(*args, **kwargs):
    """Z3's answer to the window's question, noted."""
    poses = ask(*args, **kwargs)
    found.append(poses is not None)
    return poses


def watched(ep, seed, observer=None, min_met=exact_finish.MIN_MET):
    """The finish as shipped; where it keeps nothing in a small room, the window's question asked on the side (in a
    room of at most `window.SIZE` free objects the window is the whole room: only the fixed objects are kept)."""
    out = finish(ep, seed, observer, min_met)
    if out is ep and exact_finish.wanted(ep, min_met) and exact_finish.small(ep.problem.plan, len(ep.problem.fixed)):
        assert set(window(ep)) == set(ep.problem.fixed)
        start, found[:] = time.perf_counter(), []
        new = one_more(ep, seed, exact_finish.WORK, exact_finish.STALL_S)
        asked.append((current, ep.problem.constraints.count() - met(ep), found[0], new is not ep,
                      time.perf_counter() - start))
    return out


smt.one_more_met = counted
exact_finish.finished_exactly = watched
lines = ["set: runs asked / a layout found / kept by the judge (of them with one constraint broken) / seconds per ask"]
for current in SETS:
    for plan, seed in finish_runs(current):
        get_solver("plan2place").solve(plan, seed=seed)
    mine = [a for a in asked if a[0] == current]
    one = Counter(a[3] for a in mine if a[1] == 1)
    secs = sorted(a[4] for a in mine) or [0.0]
    lines.append(f"{current}: {len(mine)} / {sum(a[2] for a in mine)} / {sum(a[3] for a in mine)} ({one[True]} of "
                 f"{sum(one.values())}) / {secs[0]:.2f}-{secs[-1]:.2f}, median {secs[len(secs) // 2]:.2f}")
(HERE / "small-rooms.txt").write_text("\n".join(lines) + "\n")
print("\n".join(lines))
