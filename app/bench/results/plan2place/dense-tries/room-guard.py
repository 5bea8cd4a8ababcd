"""Tried for `dense`, not kept (room-guard.txt): a room guard on top of the reach guard. Each pending object's
relaxed-legal poses are kept as a mask, narrowed by each placed body; a pick that would leave some pending object with none (which had some) is
passed over for the next most wanted one that also keeps reach. Off-sample diagnosis plans (i % step == step // 2), 2
seeds. PYTHONPATH=. python app/bench/results/plan2place/dense-tries/room-guard.py dense 20 [--on]"""
import sys
from pathlib import Path

import numpy as np

from models.placement import greedy as G
from models.placement.candidates import OVERLAP_TOL

ON = "--on" in sys.argv
orig_guarded = G.Episode.guarded
STATS = {"rejected": 0, "steps": 0}

def room_masks(ep):
    if not hasattr(ep, "_room"):
        ep._room = {}
    done = {p.id for p in ep.placed} | set(ep.failed)
    for o in ep.order[ep.i + 1:]:
        if o.id in ep.problem.fixed or o.id in done:
            continue
        if o.id not in ep._room:
            cands = ep.scorer.bodies(o)[0]
            ep._room[o.id] = [G.hard_filter(ep.scorer, o, ep.placed, cands, ep.scorer.swept(o), False)[0], len(ep.placed)]
        mask, upto = ep._room[o.id]
        for p in ep.placed[upto:]:  # narrow by the bodies placed since
            for idx, area in ep.scorer.swept(o).overlaps(p.body[None]):
                mask[idx[area > OVERLAP_TOL]] = False
        ep._room[o.id][1] = len(ep.placed)
    return {oid: m for oid, (m, _) in ep._room.items() if oid not in done and oid != ep.order[ep.i].id}

def kills(ep, masks, pose):
    for oid, mask in masks.items():
        if not mask.any():
            continue
        o = ep.problem.plan.object(oid)
        hit = np.zeros(len(mask), bool)
        for idx, area in ep.scorer.swept(o).overlaps(pose.body[None]):
            hit[idx[area > OVERLAP_TOL]] = True
        if not (mask & ~hit).any():
            return True
    return False

def guarded(self, opts, order):
    pick = orig_guarded(self, opts, order)
    if not ON:
        return pick
    STATS["steps"] += 1
    masks = room_masks(self)
    top = order[:G.GUARD_TRIES]
    keep = self.keeping(opts, top)
    cand = [pick] + [int(k) for k, ok in zip(top, keep) if ok and k != pick]
    for k in cand:
        pose = self.scorer.place(opts.obj, *(float(v) for v in opts.cands[opts.feasible[k]]))
        if not kills(self, masks, pose):
            if k != pick:
                STATS["rejected"] += 1
            return k
    return pick
G.Episode.guarded = guarded

sys.path.insert(0, str(Path(__file__).parent))
from diagnosis_runs import run  # noqa: E402
print(run(sys.argv[1], int(sys.argv[2]), "ON" if ON else "OFF", f"/tmp/rg-{sys.argv[1]}-{'on' if ON else 'off'}.npy"), STATS)
