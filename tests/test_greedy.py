"""The greedy placer: lowest immediate energy per object, legal layouts, fixed poses kept, one step each."""

import numpy as np

from models.datasets import load_dataset
from models.energy.exact import layout_energy
from models.metrics import scene_metrics
from models.placement import PlacementProblem, get_solver
from models.placement.greedy import Episode, GreedySolver


def _plans(n=3):
    recs = sorted(load_dataset("seen", "validation"), key=lambda r: len(r.plan.objects))
    return [r.plan for r in recs[:: max(len(recs) // n, 1)][:n]]


def test_greedy_places_everything_legally_and_reports_each_step():
    for plan in _plans():
        steps = []
        layout = get_solver("greedy").solve(plan, seed=1, observer=steps.append)
        m = scene_metrics(plan, layout, PlacementProblem.from_plan(plan))
        assert m.cnt == 1.0 and m.collisions == 0 and m.oob == 0.0
        order = [o.id for o in PlacementProblem.from_plan(plan).order]
        ids = [s.object_id for s in steps]  # one step per object, then the repairs' steps if any
        assert ids[:len(order)] == order and set(ids[len(order):]) <= set(order)
        for s in steps:
            finite = np.isfinite(s.scores)
            assert abs(s.scores[finite].sum() - 1) < 1e-6  # a distribution over the legal candidates
            assert "total" in s.terms


def test_greedy_step_is_the_lowest_immediate_energy():
    plan = _plans(1)[0]
    ep = Episode(plan)
    opts = ep.options()
    layout = GreedySolver(repair=False).solve(plan, seed=0)
    first = next(p for p in layout.placements if p.id == opts.obj.id)
    chosen = opts.cands[opts.feasible]
    k = np.flatnonzero((np.abs(chosen[:, 0] - first.x) < 1e-3) & (np.abs(chosen[:, 1] - first.z) < 1e-3)
                       & (chosen[:, 2] % 360 == first.rotation % 360))
    assert len(k) == 1  # the pose is one of the legal candidates ...
    assert opts.terms["total"][k[0]] == opts.terms["total"].min()  # ... and one of lowest immediate energy


def test_greedy_keeps_fixed_poses_and_its_energy_is_the_judges():
    plan = _plans(1)[0]
    first = get_solver("greedy").solve(plan, seed=0)
    moved = first.placements[-1]
    pose = (moved.x, moved.z, moved.rotation)
    again = get_solver("greedy").solve(plan, seed=0, fixed={moved.id: pose})
    kept = next(p for p in again.placements if p.id == moved.id)
    assert (kept.x, kept.z, kept.rotation) == pose
    assert layout_energy(plan, first.placements).total < layout_energy(plan, []).total  # placing beats leaving out


def test_fast_hard_filter_is_candidate_scorers():
    from models.geometry import SweptBoxes
    from models.placement.greedy import hard_filter
    for plan in _plans(4):
        ep = Episode(plan)
        rng = np.random.default_rng(1)
        while not ep.done:
            obj = ep.order[ep.i]
            for strict in (True, False):
                cands, scores, _ = ep.scorer.evaluate(obj, ep.placed, strict=strict)
                cands_fast, body = ep.scorer.bodies(obj)
                ok, _ = hard_filter(ep.scorer, obj, ep.placed, cands_fast, SweptBoxes(body), strict)
                assert np.array_equal(cands_fast, cands)
                assert (ok == np.isfinite(scores)).all()
            opts = ep.options()
            ep.apply(opts, int(rng.integers(len(opts.feasible))) if len(opts.feasible) else None)


def test_candidate_grid_is_the_meshgrid_of_unique_axes():
    """CandidateScorer.grid builds the candidates without np.unique / meshgrid: the same array as before."""
    from models.placement.candidates import ROTATIONS, CandidateScorer

    def axis(step, half, length):
        if 2 * half > length + 1e-9:
            return np.empty(0)
        return np.unique(np.round(np.concatenate([np.arange(half, length - half, step), [length - half]]), 4))

    for plan in _plans(6):
        scorer = CandidateScorer(PlacementProblem.from_plan(plan))
        for obj in plan.objects:
            parts = []
            for rot in ROTATIONS:
                hx, hz = (obj.size.x / 2, obj.size.z / 2) if rot in (0.0, 180.0) else (obj.size.z / 2, obj.size.x / 2)
                xs, zs = axis(scorer.step, hx, scorer.width), axis(scorer.step, hz, scorer.depth)
                if len(xs) and len(zs):
                    gx, gz = np.meshgrid(xs, zs, indexing="ij")
                    parts.append(np.stack([gx.ravel(), gz.ravel(), np.full(gx.size, rot)], axis=1))
            want = np.concatenate(parts) if parts else np.empty((0, 3))
            assert np.array_equal(scorer.candidates(obj), want)
    rng = np.random.default_rng(0)
    scorer = CandidateScorer(PlacementProblem.from_plan(_plans(1)[0]))
    for _ in range(20000):  # odd sizes and rooms, where the last grid step meets the far wall
        half, length = round(rng.uniform(0.05, 2.0), int(rng.integers(1, 6))), round(rng.uniform(0.5, 8), int(rng.integers(1, 6)))
        assert np.array_equal(scorer._axis(half, length), axis(scorer.step, half, length))


def test_a_solve_runs_blas_on_one_thread_and_puts_the_setting_back():
    from threadpoolctl import threadpool_limits

    seen = []
    with threadpool_limits(limits=2, user_api="blas"):  # as numpy has it on a 2-core machine, whatever this one is
        assert blas_threads() == {2}
        for name in ("greedy", "plan2place", "dfs"):
            get_solver(name).solve(_plans(1)[0], seed=0, observer=lambda step: seen.append(blas_threads()))
        assert blas_threads() == {2}
    assert seen and all(s == {1} for s in seen)


def test_solves_in_worker_threads_overlapping_share_the_one_thread_limit_and_the_last_puts_numpys_setting_back():
    """As the studio solves: in worker threads, maybe two at once, after the main thread has solved too."""
    import threading

    from threadpoolctl import threadpool_limits

    plan, seen = _plans(1)[0], {}

    def solve(name, started, go_on):
        def observe(step):
            seen.setdefault(name, set()).update(blas_threads())
            started.set()
            assert go_on.wait(timeout=60)  # held open until the test lets it go on
        get_solver("greedy").solve(plan, seed=0, observer=observe)

    def begin(name):
        started, go_on = threading.Event(), threading.Event()
        thread = threading.Thread(target=solve, args=(name, started, go_on))
        thread.start()
        assert started.wait(timeout=60)
        return thread, go_on

    numpys = threadpool_limits(limits=2, user_api="blas")  # as on 2 cores; this thread now holds threadpoolctl's control
    try:
        get_solver("greedy").solve(plan, seed=0)  # the main thread solves too
        (first, go_first), (second, go_second) = begin("first"), begin("second")
        go_first.set()
        first.join()  # the first ends while the second is under way
        assert blas_threads() == {1}
        go_second.set()
        second.join()
        assert seen == {"first": {1}, "second": {1}}
        assert blas_threads() == {2}
    finally:
        numpys.restore_original_limits()


def blas_threads() -> set[int]:
    """The thread counts of the BLAS libraries loaded in this process."""
    from threadpoolctl import threadpool_info
    return {lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"}
