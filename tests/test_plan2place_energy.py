"""The incremental set-ups of the vectorised energy (CandidateEnergy.after, .without) equal fresh ones."""

import numpy as np

from models.datasets import load_dataset
from models.energy.vectorised import CandidateEnergy
from models.placement.greedy import Episode


def test_incremental_setup_equals_a_fresh_one():
    recs = load_dataset("seen", "validation")
    for plan in [recs[3].plan, recs[200].plan, recs[555].plan]:
        ep = Episode(plan)
        rng = np.random.default_rng(0)
        while not ep.done:
            opts = ep.options()
            fresh = CandidateEnergy(ep.problem, ep.placed, pending=ep.pending())
            if len(opts.feasible):
                want = fresh.score(opts.obj, opts.cands[opts.feasible])
                for k, v in want.items():
                    np.testing.assert_allclose(opts.terms[k], v, atol=1e-9, err_msg=k)
            # a random legal pick (also a collision-free but poor one) keeps the test off greedy's path
            ep.apply(opts, int(rng.integers(len(opts.feasible))) if len(opts.feasible) else None)


def test_a_setup_without_one_object_equals_a_fresh_one():
    recs = load_dataset("seen", "validation")
    for plan in [recs[3].plan, recs[200].plan, recs[555].plan]:
        ep = Episode(plan)
        ep.finish_greedily()
        full = CandidateEnergy(ep.problem, ep.placed)
        for p in ep.placed:
            others = [q for q in ep.placed if q is not p]
            got, fresh = full.without(p.id, pending={p.id}), CandidateEnergy(ep.problem, others, pending={p.id})
            for k in ("rel_sum", "rel_n", "collision_sum", "oob_sum", "aff_sum"):
                assert abs(getattr(got, k) - getattr(fresh, k)) < 1e-9, k
            assert np.array_equal(got.blocked, fresh.blocked) and np.array_equal(got.reach, fresh.reach)
            obj = plan.object(p.id)
            cands = ep.scorer.candidates(obj)[::7]
            want = fresh.score(obj, cands)
            for k, v in got.score(obj, cands).items():
                np.testing.assert_allclose(v, want[k], atol=1e-9, err_msg=k)


def test_per_step_shortcuts_compute_the_same_numbers():
    """The speed work's shortcuts, each against what it replaces: boxes of the candidate grid per rotation,
    the cell ranges of an intersection as max / min of the boxes' ranges, the windowed blocked grid, and the
    step's shared cache (soft score + energy) against a cold `CandidateEnergy.score`."""
    from models.energy import navigation as nav
    from models.energy.vectorised import _intersect
    from models.geometry import boxes
    from models.placement.candidates import grid_boxes
    recs = load_dataset("seen", "validation")
    rng = np.random.default_rng(0)
    for plan in [recs[3].plan, recs[200].plan, recs[555].plan]:
        ep = Episode(plan)
        while not ep.done:
            obj = ep.order[ep.i]
            cands = ep.scorer.candidates(obj)
            assert np.array_equal(grid_boxes(cands, obj.size.x, obj.size.z),
                                  boxes(cands[:, 0], cands[:, 1], obj.size.x, obj.size.z, cands[:, 2]))
            energy = ep._energy
            cut = np.sort(rng.uniform(-0.5, max(plan.room.width, plan.room.depth) + 0.5, (200, 2, 2)), axis=1)
            cut = cut.transpose(0, 2, 1).reshape(200, 4)[:, [0, 2, 1, 3]]  # xmin, zmin, xmax, zmax
            for strip in energy.door_boxes + [cut[::-1]] + list(cut[:8]):  # one strip for all, one each
                assert np.array_equal(energy._reachable_strip(strip, energy.reach_count.cells(cut)),
                                      energy._reachable_strip(strip, cut))
                want = energy.reach_count.count(_intersect(np.broadcast_to(strip, cut.shape), cut))
                c0, c1, d0, d1 = energy.reach_count.cells(cut)
                s0, s1, t0, t1 = energy.reach_count.cells(np.asarray(strip))
                got = energy.reach_count.count_cells(np.maximum(s0, c0), np.minimum(s1, c1), np.maximum(t0, d0),
                                                     np.minimum(t1, d1))
                assert np.array_equal(got, want)
            fixed = energy.door_boxes + list(cut[:8])  # strips the same for every candidate (compiled)
            door_open, reached = energy._strips_reached(fixed, len(energy.door_boxes), energy.reach_count.cells(cut))
            by_counts = [energy._reachable_strip(strip, cut) for strip in fixed]
            assert np.array_equal(door_open, np.any(by_counts[:len(energy.door_boxes)], axis=0))
            assert np.array_equal(reached, np.sum(by_counts[len(energy.door_boxes):], axis=0))
            assert np.array_equal(energy.blocked, nav.blocked_by_boxes(energy.grid, energy.bodies))
            assert np.array_equal(energy.reach, nav.reachable_space(energy.grid, energy.blocked, plan.room))
            opts = ep.options()
            if len(opts.feasible):
                cold = energy.score(opts.obj, opts.cands[opts.feasible])  # no shared cache
                for k, v in cold.items():
                    assert np.array_equal(opts.terms[k], v), k
                soft = ep.scorer.soft_scores(opts.obj, opts.cands[opts.feasible], ep.placed)[0]
                assert np.array_equal(opts.soft, soft)
            ep.apply(opts, int(rng.integers(len(opts.feasible))) if len(opts.feasible) else None)


def test_blocked_cells_by_windows_equal_every_cell_against_every_box():
    """The compiled window kernels (`blocked_by_boxes`, adding a box, taking one away) against every cell tested
    against every box with numpy."""
    from models.energy import navigation as nav
    rng = np.random.default_rng(3)
    for width, depth in [(3.0, 4.2), (6.35, 5.1)]:
        grid = nav.Grid(width, depth)
        mesh = gx, gz = grid.mesh()
        r = nav.ROBOT_RADIUS

        def every_cell(boxes):
            b = boxes[:, None, None, :]
            dx = np.maximum(0, np.maximum(b[..., 0] - gx, gx - b[..., 2]))
            dz = np.maximum(0, np.maximum(b[..., 1] - gz, gz - b[..., 3]))
            walls = (gx < r) | (gz < r) | (gx > width - r) | (gz > depth - r)
            return walls | (dx * dx + dz * dz <= r * r + 1e-12).any(axis=0)

        for _ in range(20):
            lo = rng.uniform(-0.5, [width, depth], size=(int(rng.integers(1, 8)), 2))
            boxes = np.hstack([lo, lo + rng.uniform(0.01, 2.0, size=lo.shape)])
            want = every_cell(boxes)
            assert np.array_equal(nav.blocked_by_boxes(grid, boxes), want)
            assert np.array_equal(nav.blocked_with(mesh, every_cell(boxes[:-1]), boxes[-1]), want)
            assert np.array_equal(nav.blocked_without(grid, mesh, want, boxes[-1], boxes[:-1]), every_cell(boxes[:-1]))


def test_the_repairs_moves_carry_an_energy_setup_equal_to_a_fresh_one():
    """The polish and the companions' pass hand the set-up a move was scored with on to the next move."""
    from models.placement import habits
    from models.placement.polish import Standing, _relocation, broken
    recs = load_dataset("seen", "train")
    checked = 0
    for plan in [r.plan for r in recs[:80]]:
        ep = Episode(plan)
        ep.finish_greedily()
        now, kept = Standing(ep), habits.Habits(plan, ep.placed)
        moves = [_relocation(ep, now, oid) for oid in broken(ep)[:1]]
        moves += [habits._move(ep, now, kept, p, kept.kept()) for p in ep.placed[:3] if kept.types[p.id] in kept.comp]
        for move in [m for m in moves if m is not None][:1]:
            now.moved(move)
            fresh = CandidateEnergy(ep.problem, ep.placed)
            obj = ep.problem.plan.object(ep.placed[0].id)
            cands = ep.scorer.grid(obj)[0]
            want, got = fresh.without(obj.id).score(obj, cands), now.setup.without(obj.id).score(obj, cands)
            for k, v in want.items():
                np.testing.assert_allclose(got[k], v, atol=1e-9, err_msg=k)
            checked += 1
    assert checked >= 10


def test_the_energies_a_step_remembers_are_those_its_pose_is_given_afresh():
    """`CandidateEnergy.remember` keeps, for the pose a step picks, the relational energies `score` computed for
    every candidate; they must equal, to the bit, what `_own` and `_pair` compute for that one pose."""
    from models.constraints.evaluate import Poses
    recs = load_dataset("seen", "validation")
    rng, checked = np.random.default_rng(1), 0
    for plan in [recs[3].plan, recs[200].plan, recs[555].plan]:
        ep = Episode(plan)
        while not ep.done:
            opts = ep.options()
            pick = int(rng.integers(len(opts.feasible))) if len(opts.feasible) else None
            if pick is not None:
                kept = CandidateEnergy(ep.problem, ep.placed, pending=ep.pending())
                kept.remember(opts.shared, pick)
                cold = CandidateEnergy(ep.problem, ep.placed, pending=ep.pending())
                for key, value in kept._pairs.items():
                    size = {o.id: (o.size.x, o.size.z) for o in plan.objects}
                    if len(key) == 5:  # (placement, id, x, z, rotation)
                        name, oid, x, z, r = key
                        fresh = cold._own(oid, name, Poses.one(x, z, r, *size[oid]))
                    else:  # (relation, a, b, a's x, z, rotation, b's)
                        name, a, b, *pa = key
                        fresh = cold._pair(name, a, b, Poses.one(*pa[:3], *size[a]), Poses.one(*pa[3:], *size[b]))
                    assert fresh == value, key
                    checked += 1
            ep.apply(opts, pick)
    assert checked >= 20


def test_the_floor_never_exceeds_the_energy_of_a_layout_that_completes_it():
    """`CandidateEnergy.floor`: with some objects taken away, a lower bound on the energy of the whole layout (the
    polish rejects a make-way move by it); with none taken away, the energy itself; an object the layout leaves
    out is charged, and so is a task object the robot cannot reach with those objects alone."""
    from models.energy.weights import WEIGHTS
    recs = load_dataset("dense")
    rng = np.random.default_rng(2)
    tight = cut_off = 0
    for plan in [r.plan for r in recs[:12]]:
        ep = Episode(plan)
        ep.finish_greedily()
        full = CandidateEnergy(ep.problem, ep.placed)
        terms = full.terms()
        assert abs(full.floor(full) - terms["total"]) < 1e-9
        assert full.floor(full) >= WEIGHTS["missing"] * len(ep.failed) / len(plan.objects) - 1e-12
        for _ in range(5):
            gone = rng.choice(len(ep.placed), size=int(rng.integers(1, 4)), replace=False)
            part = CandidateEnergy(ep.problem, [p for i, p in enumerate(ep.placed) if i not in gone])
            assert part.floor(full) <= terms["total"] + 1e-12
            tight += part.floor(full) > terms["total"] - 0.05
            cut_off += part._cut_off() > 0
    assert tight > 0 and cut_off > 0  # the bound is not vacuous; its navigation part is tried
