"""Do the `dense` plans admit a layout that places every object AND keeps every task object reachable?
A diagnosis, not a solver. It answers by search: DFS's search with one more rule. A pose is taken only if every
task object placed so far, and the pose's own object, stays reachable from the doorway (reach.Reach, Key_NAV's
test). Reach only shrinks as objects are added, so the rule never cuts off a layout that meets both. The search
is still incomplete (it branches over the `BRANCH` best such poses, within `BUDGET_S` per plan): a miss is no
proof that the plan has no such layout.

    python app/bench/results/plan2place/dense-feasible/search.py   # -> search.md (diagnosis plans of `dense`)
"""

import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "lookahead-bound"))
BRANCH, BUDGET_S, PLANS = 5, 30.0, 20


def search(plan, seed: int = 0, budget: float = BUDGET_S, max_nodes: int | None = None):
    """(the layout that places the most objects with every placed task object reachable, seconds, nodes);
    the search stops after `budget` seconds or `max_nodes` nodes."""
    from models.placement.candidates import CandidateScorer
    from models.placement.dfs import MIN_SPREAD, NO_ROOM
    from models.placement.problem import PlacementProblem
    from models.placement.reach import Reach
    from models.placement.result import make_layout

    start = time.perf_counter()
    problem = PlacementProblem.from_plan(plan)
    scorer, reach, order = CandidateScorer(problem), Reach(problem), problem.order
    rng = np.random.default_rng(seed)
    best = {"placed": [], "failed": {}, "key": -1}
    nodes = [0]

    def picks(obj, placed):
        cands, scores, _ = scorer.evaluate(obj, placed, strict=True)
        if not np.isfinite(scores).any():
            cands, scores, _ = scorer.evaluate(obj, placed, strict=False)
        scores = scores + rng.uniform(0, 1e-3, size=len(scores))
        base = reach.blocked(placed)
        out = []
        for idx in np.argsort(-scores):
            if not np.isfinite(scores[idx]) or len(out) == BRANCH:
                break
            if any(cands[idx, 2] == cands[j, 2] and np.hypot(*(cands[idx, :2] - cands[j, :2])) < MIN_SPREAD
                   for j in out):
                continue
            pose = scorer.place(obj, *(float(v) for v in cands[idx]))
            if reach.out_with(placed, base, pose) == 0:
                out.append(int(idx))
        return cands, out

    def over() -> bool:
        return time.perf_counter() - start > budget or (max_nodes is not None and nodes[0] >= max_nodes)

    def dfs(i, placed, failed) -> bool:
        nodes[0] += 1
        if i == len(order) or over():
            if len(placed) > best["key"]:
                best.update(placed=list(placed), failed=dict(failed), key=len(placed))
            return i == len(order) and not failed
        obj = order[i]
        cands, chosen = picks(obj, placed)
        if not chosen:
            return dfs(i + 1, placed, {**failed, obj.id: NO_ROOM})
        for idx in chosen:
            placed.append(scorer.place(obj, *(float(v) for v in cands[idx])))
            if dfs(i + 1, placed, failed):
                return True
            placed.pop()
            if over():
                break
        return False

    dfs(0, [], {})
    poses = {p.id: (p.x, p.z, p.rotation) for p in best["placed"]}
    layout = make_layout(problem, poses, best["failed"], "reach-dfs", seed, time.perf_counter() - start,
                         default_reason="search budget ran out")
    return layout, time.perf_counter() - start, nodes[0]


def one(k_plan):
    from models.metrics.placement import scene_metrics
    from models.placement import get_solver
    k, plan = k_plan
    layout, secs, nodes = search(plan)
    row = {"plan": k, "objects": len(plan.objects), "seconds": secs, "nodes": nodes}
    m = scene_metrics(plan, layout)
    row.update(cnt=m.cnt, key_nav=m.key_nav)
    for name in ("dfs", "plan2place"):
        mm = scene_metrics(plan, get_solver(name).solve(plan, seed=0))
        row[f"{name}_cnt"], row[f"{name}_key_nav"] = mm.cnt, mm.key_nav
    return row


def main() -> None:
    from run import diagnosis_plans
    plans = diagnosis_plans("dense", PLANS)
    with ProcessPoolExecutor(2) as pool:
        rows = list(pool.map(one, enumerate(plans)))
    both = lambda c, k: c == 1.0 and (k is None or k == 1.0)  # noqa: E731
    lines = [f"Reach-kept DFS (branch {BRANCH}, {BUDGET_S:.0f} s per plan) on {len(rows)} `dense` diagnosis plans, seed 0; "
             "CNT / Key_NAV in %, beside DFS and Plan2Place on the same plan and seed", "",
             "| plan | objects | reach-kept DFS | seconds | nodes | DFS | Plan2Place |", "| --- | ---: | --- | ---: | ---: | --- | --- |"]
    pct = lambda v: "-" if v is None else f"{100 * v:.0f}"  # noqa: E731
    for r in rows:
        lines.append(f"| {r['plan']} | {r['objects']} | {pct(r['cnt'])} / {pct(r['key_nav'])} | {r['seconds']:.1f} | "
                     f"{r['nodes']} | {pct(r['dfs_cnt'])} / {pct(r['dfs_key_nav'])} | "
                     f"{pct(r['plan2place_cnt'])} / {pct(r['plan2place_key_nav'])} |")
    n = len(rows)
    lines += ["", f"every object placed and every task object reachable: reach-kept DFS {sum(both(r['cnt'], r['key_nav']) for r in rows)} "
              f"of {n} plans, DFS {sum(both(r['dfs_cnt'], r['dfs_key_nav']) for r in rows)}, Plan2Place "
              f"{sum(both(r['plan2place_cnt'], r['plan2place_key_nav']) for r in rows)}",
              f"mean CNT / Key_NAV: reach-kept DFS {pct(np.mean([r['cnt'] for r in rows]))} / "
              f"{pct(np.mean([r['key_nav'] for r in rows if r['key_nav'] is not None]))}, DFS "
              f"{pct(np.mean([r['dfs_cnt'] for r in rows]))} / {pct(np.mean([r['dfs_key_nav'] for r in rows if r['dfs_key_nav'] is not None]))}, "
              f"Plan2Place {pct(np.mean([r['plan2place_cnt'] for r in rows]))} / "
              f"{pct(np.mean([r['plan2place_key_nav'] for r in rows if r['plan2place_key_nav'] is not None]))}"]
    (HERE / "search.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
