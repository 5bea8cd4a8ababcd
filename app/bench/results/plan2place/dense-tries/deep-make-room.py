"""Tried for `dense`, not kept (deep-make-room.txt): make_room with a second level, where a blocker that finds no legal
pose may itself displace one object not yet moved in the attempt (of its `SECOND_TRIES` best poses), which then goes
to its lowest-energy legal pose; `--deep` turns it on (without it: make_room as shipped, re-written here), and then
an attempt must leave no more task objects out of reach. 20 diagnosis plans x 2 seeds.
PYTHONPATH=. python app/bench/results/plan2place/dense-tries/deep-make-room.py dense 20 [--deep]"""
import sys, time
import numpy as np
import models.placement.repair as R
from models.placement.greedy import NO_ROOM
from models.placement.moves import displacements, legal_poses, move_step, scored
from models.energy.vectorised import CandidateEnergy
from models.datasets import load_dataset
from models.placement.base import get_solver
from app.bench.placement import score

DEEP = "--deep" in sys.argv
SECOND_TRIES = 3
STATS = {"rescued": 0, "second": 0}

def place_lowest(ep, m_obj, placed, pending):
    m_cands, legal, terms = scored(ep, m_obj, placed, pending=pending)
    if not len(legal):
        return None
    best = int(np.argmin(terms["total"]))
    return ep.scorer.place(m_obj, *(float(v) for v in m_cands[legal[best]])), (m_cands, legal, best, terms)

def place_blocker(ep, m_obj, placed, pending, frozen):
    got = place_lowest(ep, m_obj, placed, pending)
    if got is not None:
        return [got[0]], [(m_obj.id, got)], placed
    if not DEEP:
        return None
    cands = ep.scorer.bodies(m_obj)[0]
    movable = [p for p in placed if p.id not in frozen]
    for i, second in displacements(ep, m_obj, cands, ep.scorer.swept(m_obj), movable, tries=SECOND_TRIES):
        if len(second) > 1:
            continue
        rest = [p for p in placed if p.id not in second]
        if i not in legal_poses(ep, m_obj, rest, cands, ep.scorer.swept(m_obj)):
            continue
        pose = ep.scorer.place(m_obj, *(float(v) for v in cands[i]))
        trial, out = [*rest, pose], []
        for k, s in enumerate(second):
            g = place_lowest(ep, ep.problem.plan.object(s), trial, set(pending) | set(second[k + 1:]))
            if g is None:
                break
            trial.append(g[0]); out.append((s, g))
        else:
            STATS["second"] += 1
            return [pose] + [g[0] for _, g in out], [(m_obj.id, None)] + out, trial
    return None

def make_room(ep, observer=None):
    done = []
    for obj in [o for o in ep.order if ep.failed.get(o.id) == NO_ROOM and o.id not in ep.problem.fixed]:
        cands, swept = ep.scorer.bodies(obj)[0], ep.scorer.swept(obj)
        for i, blockers in displacements(ep, obj, cands, swept, ep.placed):
            pose = ep.scorer.place(obj, *(float(v) for v in cands[i]))
            placed = [p for p in ep.placed if p.id not in blockers]
            if i not in legal_poses(ep, obj, placed, cands, swept):
                continue
            placed.append(pose)
            frozen = {obj.id, *blockers}
            ok = True
            for k, mover in enumerate(blockers):
                got = place_blocker(ep, ep.problem.plan.object(mover), placed, set(blockers[k + 1:]), frozen)
                if got is None:
                    ok = False; break
                new, _, base = got
                placed = [p for p in base if p.id not in {q.id for q in new}] + new if base is not placed else placed + new
                frozen |= {q.id for q in new}
            if ok and DEEP and len(ep.reach.unreachable(placed)) > len(ep.reach.unreachable(ep.placed)):
                STATS["reach refused"] = STATS.get("reach refused", 0) + 1
                ok = False
            if ok:
                ep.placed = placed
                del ep.failed[obj.id]
                ep.energy = CandidateEnergy(ep.problem, placed).terms()["total"]
                done.append(obj.id)
                STATS["rescued"] += 1
                break
    return done
R.make_room = make_room

ds, n = sys.argv[1], int(sys.argv[2])
recs = load_dataset(ds, "validation" if ds == "seen" else None)
step = max(len(recs) // 20, 1)
off = [r for i, r in enumerate(recs) if i % step == step // 2][:n]
sol = get_solver("plan2place")
rows = []
for r in off:
    for seed in (0, 1):
        t = time.perf_counter(); lay = sol.solve(r.plan, seed=seed); dt = time.perf_counter() - t
        s = score(r.plan, lay)
        assert s["collisions"] == 0
        rows.append((s["cnt"], s["constraint_satisfaction"], s["key_nav"], s["energy"], dt / len(r.plan.objects)))
a = np.array(rows)
print("DEEP" if DEEP else "BASE", ds, "cnt %.2f cons %.2f keynav %.2f energy %.3f ms/obj %.2f" % (100 * a[:, 0].mean(), 100 * a[:, 1].mean(), 100 * a[:, 2].mean(), a[:, 3].mean(), 1000 * np.median(a[:, 4])), STATS)
np.save(f"/tmp/exp/deep-{ds}-{'on' if DEEP else 'off'}.npy", a)
