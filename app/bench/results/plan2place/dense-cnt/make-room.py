"""Can `make_room` place more of what Plan2Place leaves out on `dense` without losing reach? Variants of it, on the 20
`dense` diagnosis plans x 2 seeds (never the bench's or fresh plans): more poses tried (`tries`), the front strips'
occupants counted as in the way (`strips`, as the polish's make-way moves do), the objects making way placed where they
meet the most constraints first (`most`), a move kept only if it reaches no fewer task objects (`reach`), and
`restore_access` run before it (`access_first`), so that what it keeps is the access restored. Prints, per variant, the
objects left out, Key_NAV, constraints met, energy, CPU seconds and how the tries ended. Run from a tree's root:

    PYTHONPATH=. python app/bench/results/plan2place/dense-cnt/make-room.py > app/bench/results/plan2place/dense-cnt/make-room.txt
"""
import json
import sys
import time
from pathlib import Path

import numpy as np

from app.bench.placement import score
from models.energy.vectorised import CandidateEnergy
from models.geometry import SweptBoxes
from models.placement import polish as P
from models.placement import repair as R
from models.placement.base import get_solver
from models.placement.greedy import NO_ROOM, hard_filter
from models.placement.groups import regroup
from models.placement.habits import keep_companions
from models.placement.moves import displacements, legal_poses, scored
from models.placement.ties import steady

sys.path.insert(0, str(Path(__file__).parent.parent / "lookahead-bound"))
from run import diagnosis_plans  # noqa: E402

CFG: dict = {}
STATS: dict = {}
SHIPPED_MAKE_ROOM, SHIPPED_REPAIR = R.make_room, R.repair


def bump(k):
    STATS[k] = STATS.get(k, 0) + 1


def reached(ep, placed) -> int:
    return sum(p.id in ep.reach.task for p in placed) - len(ep.reach.unreachable(placed))


def make_room(ep, observer=None):
    """The shipped `make_room` with the variant's changes (its steps are not shown: no observer here)."""
    if not CFG.get("on"):
        return SHIPPED_MAKE_ROOM(ep, observer)
    done = []
    for obj in [o for o in ep.order if ep.failed.get(o.id) == NO_ROOM and o.id not in ep.problem.fixed]:
        cands, body = ep.scorer.bodies(obj)
        swept = ep.scorer.swept(obj)
        before = reached(ep, ep.placed)
        for i, blockers in displacements(ep, obj, cands, swept, ep.placed, tries=CFG["tries"],
                                         strips=CFG.get("strips", False)):
            bump("tries")
            pose = ep.scorer.place(obj, *(float(v) for v in cands[i]))
            placed = [p for p in ep.placed if p.id not in blockers]
            legal = hard_filter(ep.scorer, obj, placed, cands[[i]], SweptBoxes(body[[i]]))[0][0] if CFG.get("strips") \
                else i in legal_poses(ep, obj, placed, cands, swept)
            if not legal:
                bump("pose illegal")
                continue
            placed.append(pose)
            memo: dict = {}
            for k, mover in enumerate(blockers):
                m_obj = ep.problem.plan.object(mover)
                if CFG.get("most"):
                    m_cands, legal, most = P._legal_among(ep, mover, placed, memo)
                    legal = legal[most == most.max()] if len(legal) else legal
                else:
                    m_cands, legal, _ = scored(ep, m_obj, placed, pending=set(blockers[k + 1:]))
                if not len(legal):
                    break
                terms = CandidateEnergy(ep.problem, placed, pending=set(blockers[k + 1:])).score(m_obj, m_cands[legal])
                best = int(np.argmin(steady(terms["total"])))
                placed.append(ep.scorer.place(m_obj, *(float(v) for v in m_cands[legal[best]])))
            else:
                if CFG.get("reach") and reached(ep, placed) < before:
                    bump("reach lost")
                    continue
                terms = CandidateEnergy(ep.problem, [p for p in placed if p is not pose], pending=()).score(
                    obj, cands[[i]], nav_mode="exact")
                ep.placed = placed
                del ep.failed[obj.id]
                ep.energy, ep.terms = float(terms["total"][0]), {t: float(v[0]) for t, v in terms.items()}
                done += [obj.id, *blockers]
                bump("placed")
                break
            bump("one making way has no legal pose")
    return done


def repair(ep, observer=None):
    if not CFG.get("access_first"):
        return SHIPPED_REPAIR(ep, observer)
    return R.restore_access(ep, observer) + R.make_room(ep, observer) + R.polish(ep, observer) + \
        regroup(ep, observer) + keep_companions(ep, observer)


R.make_room, R.repair = make_room, repair
VARIANTS = [{}, {"on": True, "tries": 5}, {"on": True, "tries": 20}, {"on": True, "tries": 100},
            {"on": True, "tries": 1000}, {"on": True, "tries": 5, "reach": True},
            {"on": True, "tries": 100, "reach": True}, {"on": True, "tries": 1000, "reach": True},
            {"on": True, "tries": 5, "strips": True, "reach": True},
            {"on": True, "tries": 20, "strips": True, "most": True, "reach": True},
            {"on": True, "tries": 100, "strips": True, "most": True, "reach": True},
            {"on": True, "tries": 20, "strips": True, "reach": True, "access_first": True},
            {"on": True, "tries": 100, "strips": True, "most": True, "reach": True, "access_first": True}]

if __name__ == "__main__":
    plans = diagnosis_plans("dense", 20)
    solver = get_solver("plan2place")
    solver.solve(plans[0], seed=0)
    dfs_out = sum(len(get_solver("dfs").solve(p, seed=s).unplaced) for p in plans for s in (0, 1))
    print(f"20 dense diagnosis plans x 2 seeds, {sum(len(p.objects) for p in plans) * 2} objects; DFS leaves {dfs_out} out")
    for v in VARIANTS:
        CFG.clear(), CFG.update(v), STATS.clear()
        out, rows, t = 0, [], time.process_time()
        for p in plans:
            for seed in (0, 1):
                layout = solver.solve(p, seed=seed)
                out += len(layout.unplaced)
                rows.append(score(p, layout))
        mean = lambda k, f=100: f * float(np.mean([r[k] for r in rows if r[k] is not None]))  # noqa: E731
        print(f"{json.dumps(v) if v else 'shipped'}: left out {out}, Key_NAV {mean('key_nav'):.2f}, constraints "
              f"{mean('constraint_satisfaction'):.2f}, energy {mean('energy', 1):.3f}, CPU {time.process_time() - t:.1f} s, "
              f"tries {dict(STATS)}", flush=True)
