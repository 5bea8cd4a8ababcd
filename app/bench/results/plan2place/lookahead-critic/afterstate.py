"""Would after-state inputs carry what the look-ahead knows? A diagnosis, no fitting: on `seen` training plans, in
the shipped policy's episodes, each step's 8 lowest-energy candidates (and the policy's pick) are judged by the
look-ahead (greedy completion) and described by three after-state numbers: how many legal poses the next object
keeps once the candidate is placed, the mean over every object still to come of log(1 + its legal poses), and the
sum over the objects still to come of the most constraints each could meet at one of its legal poses (`polish.met`
with the objects placed so far).
Per-step regret (final energy of the pick above the best judged) of greedy's pick, the policy's, and the judged
candidate of lowest immediate energy that keeps the most room by each number (ties: lower energy first).

    PYTHONPATH=. python app/bench/results/plan2place/lookahead-critic/afterstate.py [EPISODES]   # -> afterstate.md
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from models.datasets import load_dataset
from models.placement.greedy import Episode, hard_filter
from models.placement.plan2place.features import choose_subset, observe
from models.placement.plan2place.policy import shipped_policy, shipped_weights
from models.placement.polish import met

HERE = Path(__file__).parent
LOWEST, SEED = 8, 7


def legal_mask(ep: Episode, obj) -> np.ndarray:
    cands = ep.scorer.bodies(obj)[0]
    return hard_filter(ep.scorer, obj, ep.placed, cands, ep.scorer.swept(obj), True)[0]


def room_after(ep: Episode, opts, pick: int) -> tuple[int, float, int]:
    """(legal poses of the next object, mean log(1 + legal poses) over the objects still to come, the most
    constraints each of those could meet, summed) after `pick`."""
    twin = ep.fork()
    twin.apply(opts, int(pick))
    rest = twin.order[twin.i:]
    if not rest:
        return 0, 0.0, 0
    legal = [np.flatnonzero(legal_mask(twin, o)) for o in rest]
    meetable = sum(int(met(twin, o.id, idx, twin.placed).max()) for o, idx in zip(rest, legal) if len(idx))
    return len(legal[0]), float(np.mean(np.log1p([len(i) for i in legal]))), meetable


def steps_of(plan, rng) -> list[dict]:
    policy, use_global = shipped_policy(), shipped_weights().use_global
    ep, out = Episode(plan), []
    while not ep.done:
        opts, pick = ep.options(), None
        if len(opts.feasible):
            subset = choose_subset(opts, rng)  # sorted by immediate energy, then random extras
            a = int(np.argmax(policy(observe(ep, opts, subset, use_global))))
            judged = sorted({*range(min(LOWEST, len(subset))), a})
            picks = subset[judged]
            finals = ep.judge(opts, picks)
            room = np.array([room_after(ep, opts, p) for p in picks])
            if np.ptp(finals) > 1e-9 and len(ep.order) - ep.i > 1:
                out.append({"finals": finals, "next": room[:, 0], "all": room[:, 1], "meetable": room[:, 2],
                            "policy": judged.index(a), "energy": opts.terms["total"][picks]})
            pick = int(subset[a])
        ep.apply(opts, pick)
    return out


def main(episodes: int) -> int:
    plans = [r.plan for r in load_dataset("seen", "train")]
    order = np.random.default_rng(SEED).permutation(len(plans))
    steps = [s for k in range(episodes) for s in steps_of(plans[order[k]], np.random.default_rng([SEED, k]))]

    def regret(pick) -> tuple[float, float]:
        r = np.array([s["finals"][pick(s)] - s["finals"].min() for s in steps])
        return float(r.mean()), float((r <= 1e-9).mean())

    def most_room(key):
        return lambda s: int(np.lexsort((s["energy"], -s[key]))[0])

    rows = {"greedy (lowest immediate energy)": lambda s: 0, "the shipped policy": lambda s: s["policy"],
            "most room for the next object": most_room("next"), "most room for every object to come": most_room("all"),
            "most constraints the objects to come could meet": most_room("meetable"),
            "the look-ahead (oracle)": lambda s: int(np.argmin(s["finals"]))}
    lines = [f"{len(steps)} steps of {episodes} `seen` training episodes where the judged candidates' look-ahead finals "
             "differ (afterstate.py); per-step regret (final energy above the best judged) and share of steps at a "
             "best judged candidate", "", "| pick | mean regret | at the best |", "| --- | ---: | ---: |"]
    lines += [f"| {name} | {regret(f)[0]:.4f} | {regret(f)[1]:.3f} |" for name, f in rows.items()]
    (HERE / "afterstate.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(int(sys.argv[1]) if len(sys.argv) > 1 else 300))
