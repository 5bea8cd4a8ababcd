"""The three baselines behind one interface: valid layouts, and no crash on malformed plans."""

import itertools

import pytest

from app.cli import main
from models.geometry import Footprint, inside_room, overlap_area
from models.metrics import scene_metrics
from models.placement import get_solver
from models.values import ConstraintPlan

SOLVERS = ["dfs", "milp", "z3"]
ROOM = {"type": "kitchen", "width": 4.2, "depth": 5.0, "doors": [{"wall": "south", "center": 1.1, "width": 0.9}]}


def plan(objects, constraints=""):
    return ConstraintPlan.model_validate({"id": "s", "room": ROOM, "constraints": constraints, "objects": [
        {"id": oid, "type": t, "size": {"x": w, "y": 1, "z": d}, "role": role} for oid, t, w, d, role in objects]})


KITCHEN = [("fridge-0", "Fridge", 0.75, 0.7, "inference"), ("countertop-0", "CounterTop", 2.4, 0.65, "anchor"),
           ("diningtable-0", "DiningTable", 1.2, 0.9, "context"), ("chair-0", "Chair", 0.5, 0.5, "context"),
           ("chair-1", "Chair", 0.5, 0.5, "context"), ("garbagecan-0", "GarbageCan", 0.4, 0.35, "context")]
KITCHEN_TEXT = ("fridge-0 | edge | near, countertop-0\ncountertop-0 | edge\ndiningtable-0 | middle\n"
                "chair-0 | middle | around, diningtable-0\nchair-1 | middle | around, diningtable-0\n"
                "garbagecan-0 | edge | near, countertop-0")


def check(p, layout):
    fps = [Footprint(q.x, q.z, q.size.x, q.size.z, q.rotation) for q in layout.placements]
    assert {o.id for o in p.objects} == {q.id for q in layout.placements} | {u.id for u in layout.unplaced}
    assert len(layout.placements) + len(layout.unplaced) == len(p.objects)
    assert all(inside_room(f, p.room.width, p.room.depth, tol=1e-3) for f in fps)
    assert all(overlap_area(a, b) < 1e-3 for a, b in itertools.combinations(fps, 2))
    assert all(u.reason for u in layout.unplaced)


@pytest.mark.parametrize("solver", SOLVERS)
def test_solver_places_a_kitchen_and_meets_most_constraints(solver):
    p = plan(KITCHEN, KITCHEN_TEXT)
    layout = get_solver(solver).solve(p, seed=0, time_budget_s=5)
    check(p, layout)
    m = scene_metrics(p, layout)
    assert layout.solver == solver and m.cnt == 1.0 and m.sr == 1.0
    assert m.constraint_satisfaction >= 0.7


MALFORMED = {
    "too large": ([("bed-0", "Bed", 6.0, 6.0, "context"), ("chair-0", "Chair", 0.5, 0.5, "anchor")], ""),
    "cycle": ([("a-0", "Chair", 0.5, 0.5, "context"), ("b-0", "Chair", 0.5, 0.5, "context")],
              "a-0 | middle | near, b-0 | far, b-0\nb-0 | middle | near, a-0 | left of, a-0"),
    "unknown names and ids": ([("a-0", "Chair", 0.5, 0.5, "context"), ("b-0", "Sofa", 2.0, 0.9, "context")],
                              "a-0 | hovering | levitate, b-0 | near, ghost-1\nghost-2 | edge\nb-0 | edge | near, b-0"),
    "unknown type": ([("x-0", "Spaceship", 1.0, 1.0, "context")], "x-0 | middle"),
}


@pytest.mark.parametrize("solver", [*SOLVERS, "greedy", "plan2place", "lookahead"])
@pytest.mark.parametrize("case", sorted(MALFORMED))
def test_malformed_plans_never_crash(solver, case):
    objects, text = MALFORMED[case]
    p = plan(objects, text)
    layout = get_solver(solver).solve(p, seed=1, time_budget_s=2)
    check(p, layout)
    if case == "too large":
        assert [u.id for u in layout.unplaced] == ["bed-0"] and "larger than the room" in layout.unplaced[0].reason
    if case == "unknown names and ids":
        assert len(layout.warnings) >= 4


@pytest.mark.parametrize("solver", ["greedy", "plan2place", "lookahead"])
def test_thirty_objects_in_a_small_room_are_placed_or_left_out_with_a_reason(solver):
    """More furniture than fits: the step-wise placers and their repairs finish, legal, every object accounted for."""
    types = [("Chair", 0.5, 0.5), ("SideTable", 0.6, 0.5), ("Shelf", 0.9, 0.4), ("Sofa", 2.0, 0.9), ("ArmChair", 0.9, 0.9)]
    objects = [(f"{t.lower()}-{k}", t, w, d, "anchor" if k == 0 else "context")
               for k in range(6) for t, w, d in types]
    p = plan(objects, "\n".join(f"{o[0]} | edge" for o in objects))
    layout = get_solver(solver).solve(p, seed=0)
    check(p, layout)
    assert len(p.objects) == 30 and layout.placements and layout.unplaced


@pytest.mark.parametrize("solver", ["milp", "z3"])
def test_place_command_runs_every_solver(tmp_path, capsys, solver):
    path = tmp_path / "plan.json"
    path.write_text(plan(KITCHEN, KITCHEN_TEXT).model_dump_json())
    assert main(["place", str(path), "--solver", solver, "--out", str(tmp_path / "layout.json")]) == 0
    assert f'"solver": "{solver}"' in (tmp_path / "layout.json").read_text()


@pytest.mark.parametrize("solver", [*SOLVERS, "greedy", "plan2place", "lookahead"])
def test_an_edit_replans_from_the_edited_point(pipeline, solver):
    """Objects placed before the first object whose constraints changed keep their poses."""
    from app.pipeline import kept_before_edit
    gen = pipeline.replan(pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0),
                          pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0).plan.constraints,
                          0, solver)
    lines = gen.plan.constraints.splitlines()
    last = lines[-1].split("|")[0].strip()
    edited_text = "\n".join(lines[:-1] + [f"{last} | middle"])
    edited = gen.plan.model_copy(update={"constraints": edited_text})
    kept = kept_before_edit(gen, edited)
    assert kept and last not in kept
    again = pipeline.replan(gen, edited_text, 0, solver)
    for oid, (x, z, r) in kept.items():
        p = again.layout.placement(oid)
        assert p is not None and abs(p.x - x) < 0.01 and abs(p.z - z) < 0.01 and p.rotation == r


@pytest.mark.parametrize("solver", ["dfs", "greedy", "plan2place"])
def test_a_drag_onto_another_object_replans_the_rest_around_it(pipeline, solver):
    """A designer drags the third object of the placing order onto the first: the dragged one stays where
    it was put, the second (clear of it) keeps its pose, the first is placed again and nothing collides."""
    from app.pipeline import kept_around_moves, pose_of
    from models.placement import PlacementProblem
    gen = pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0, solver=solver)
    first, second, dragged = (o.id for o in PlacementProblem.from_plan(gen.plan).order[:3])
    onto = gen.layout.placement(first)
    moved = pipeline.move(gen, dragged, onto.x, onto.z, 0.0)
    assert scene_metrics(moved.plan, moved.layout).collisions > 0
    kept = kept_around_moves(moved, [dragged])
    assert set(kept) == {dragged, second}
    again = pipeline.replace_around(moved, [dragged], seed=0, solver=solver)
    assert pose_of(again.layout.placement(dragged)) == pose_of(moved.layout.placement(dragged))
    assert pose_of(again.layout.placement(second)) == pose_of(gen.layout.placement(second))
    assert again.layout.placement(first) is not None and (again.layout.placement(first).x,
                                                          again.layout.placement(first).z) != (onto.x, onto.z)
    assert scene_metrics(again.plan, again.layout).collisions == 0 and not again.layout.unplaced


def test_a_re_plan_of_a_room_with_two_doors_tries_again_while_a_door_is_cut_off(pipeline, monkeypatch):
    """As when the room was generated (`place_passable`): each try keeps the designer's poses, the next seed follows
    while the furniture cuts a door off, and after the last try the first layout comes with a warning."""
    from dataclasses import replace

    from models.values import Opening
    gen = pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0)
    room = gen.plan.room.model_copy(update={"doors": [*gen.plan.room.doors, Opening(wall="north", center=1.0,
                                                                                    width=0.9)]})
    gen = replace(gen, plan=gen.plan.model_copy(update={"room": room}))
    moved = pipeline.move(gen, gen.layout.placements[0].id, 1.0, 1.0, 0.0)
    tries = []
    real = pipeline.place
    monkeypatch.setattr(pipeline, "place", lambda plan, seed, solver=None, observer=None, keep=None: (
        tries.append((seed, keep)), real(plan, seed, solver, observer, keep))[1])
    monkeypatch.setattr("app.pipeline.doors_joined", lambda room, boxes: len(tries) == 2)
    again = pipeline.replace_around(moved, [moved.layout.placements[0].id], seed=5)
    assert [seed for seed, _ in tries] == [5, 6] and tries[0][1] == tries[1][1] and again.layout.seed == 6
    tries.clear()
    monkeypatch.setattr("app.pipeline.doors_joined", lambda room, boxes: False)
    cut = pipeline.replan(moved, moved.plan.constraints + "\n", seed=5)
    assert [seed for seed, _ in tries] == [5, 6, 7, 8] and cut.layout.seed == 5
    assert "cuts one of the room's doors off" in cut.layout.warnings[-1]


def test_replacing_around_nothing_or_a_stranger_is_refused(pipeline):
    from app.pipeline import kept_around_moves
    gen = pipeline.generate("Put a chilled bread on the counter", "kitchen", seed=0, solver="greedy")
    with pytest.raises(ValueError, match="nothing to re-place around"):
        kept_around_moves(gen, [])
    with pytest.raises(ValueError, match="nothing to re-place around"):
        kept_around_moves(gen, ["sofa-9"])


def test_one_per_object_budget_rule_for_every_solver():
    from models.placement.problem import PER_OBJECT_BUDGET_S, time_budget
    p = plan(KITCHEN, KITCHEN_TEXT)
    assert time_budget(p) == pytest.approx(PER_OBJECT_BUDGET_S * len(KITCHEN))
    assert time_budget(p, 3.0) == 3.0
    for name in ("dfs", "milp", "milp_whole", "z3"):
        assert get_solver(name).time_budget_s is None  # nobody has a budget of its own


def test_milp_reads_back_only_a_feasible_solution_and_says_why():
    """HiGHS's primal status 1 means infeasible: an infeasible model must give no poses, with a reason."""
    from models.placement.formulation import Expr, build
    from models.placement.milp import MILPSolver
    from models.placement.problem import PlacementProblem
    model, ov = build(PlacementProblem.from_plan(plan(KITCHEN, KITCHEN_TEXT)))
    model.require([Expr(const=1.0)])  # 1 <= 0: no solution exists
    poses, reasons = MILPSolver().run(model, ov, seed=0, seconds=1.0)
    assert poses == {} and set(reasons) == set(ov)
    assert all("no feasible layout" in r for r in reasons.values())


def test_z3_reads_the_model_as_smtlib_text_as_it_was_built():
    """The model reaches Z3 as SMT-LIB text: bounds, a negative coefficient, an implication, a disjunction and a
    weighted soft goal must each mean what they meant in the model."""
    import z3

    from models.placement.formulation import Expr, Model
    from models.placement.smt import smtlib
    m = Model()
    x, y, s = m.var("x[a]", 0.0, 10.0), m.var("y[a]", -2.5, 2.5), m.binary("s[a,b]")
    m.require([1.5 - x])  # x >= 1.5
    m.require([x - 2 * y - 4.25], when=["s[a,b]"])  # s -> x <= 2y + 4.25
    m.any_of([[x - 2.0], [Expr({"x[a]": -1.0}, 9.0)]], when=[], tag="far")  # x <= 2 or x >= 9
    m.objective = m.objective + (1 - s) * 3.0
    text, names = smtlib(m)
    opt = z3.Optimize(ctx=(ctx := z3.Context()))
    opt.from_string(text)
    opt.add(z3.Real(names["x[a]"], ctx) >= 1.9, z3.Real(names["y[a]"], ctx) <= -1.0)
    assert opt.check() == z3.sat
    got = opt.model()
    x_, y_ = (float(got.eval(z3.Real(names[n], ctx), True).as_fraction()) for n in ("x[a]", "y[a]"))
    assert got.eval(z3.Int(names["s[a,b]"], ctx)).as_long() == 1 and 1.9 <= x_ <= 2.0 and x_ <= 2 * y_ + 4.25
    opt.add(z3.Real(names["y[a]"], ctx) <= -1.5)  # now the soft goal cannot hold: s must drop to 0
    assert opt.check() == z3.sat and opt.model().eval(z3.Int(names["s[a,b]"], ctx)).as_long() == 0


def test_z3_with_no_time_leaves_every_object_out_with_a_reason():
    from models.placement.formulation import build
    from models.placement.problem import PlacementProblem
    from models.placement.smt import Z3Solver
    model, ov = build(PlacementProblem.from_plan(plan(KITCHEN, KITCHEN_TEXT)))
    poses, reasons = Z3Solver().run(model, ov, seed=0, seconds=0.001)
    assert poses == {} and set(reasons) == set(ov)
    assert all("Z3 found no model within 0.00 s" in r or "budget (0.00 s) ran out" in r for r in reasons.values())


def test_z3_on_a_work_budget_gives_a_seed_one_layout_whatever_the_clock():
    """With a budget in Z3's own resource count (as the exact finish runs it), a solve cut short by that budget ends
    where it ends on any machine: the same layout with 10 s or 60 s on the clock, fewer objects than Z3 places with
    more work, and a reason that says the budget ran out."""
    from models.datasets import load_dataset
    from models.placement.smt import Z3Solver
    bedroom = next(r.plan for r in load_dataset("human") if r.plan.id == "human-FloorPlan313")
    cut = Z3Solver(10.0, 60_000).solve(bedroom, 3)
    assert cut.placements and cut.placements == Z3Solver(60.0, 60_000).solve(bedroom, 3).placements
    assert len(cut.placements) < len(Z3Solver(10.0, 1_000_000).solve(bedroom, 3).placements)
    assert all("360,000 units of its work) ran out" in u.reason for u in cut.unplaced)


@pytest.mark.parametrize("where", ["Optimize.check", "ModelRef.eval"])
def test_z3_interrupted_leaves_every_object_out_with_a_reason(monkeypatch, where):
    """The budget's timer interrupts Z3's Optimize; the interrupt can surface as a Z3Exception ("canceled") in
    `check()`, or in reading the model back when it fires just as `check()` returns (both seen on `dense` plans in the
    placement bench), which must not end the solve."""
    import z3

    def canceled(self, *args, **kwargs):
        raise z3.Z3Exception(b"canceled")

    cls, method = where.split(".")
    monkeypatch.setattr(getattr(z3, cls), method, canceled)
    p = plan(KITCHEN, KITCHEN_TEXT)
    layout = get_solver("z3").solve(p, seed=0)
    check(p, layout)
    assert not layout.placements and all("canceled" in u.reason for u in layout.unplaced)


def test_z3_gives_a_seed_the_same_layout_whatever_it_solved_before():
    """Each Z3 solve states its model in a context of its own: Z3's shared one kept state from the solves before, and
    the iTHOR bedroom FloorPlan313 got another layout after a solve with a kept pose in the same process."""
    from models.datasets import load_dataset
    from models.placement.smt import Z3Solver
    bedroom = next(r.plan for r in load_dataset("human") if r.plan.id == "human-FloorPlan313")
    first = Z3Solver(1.5).solve(bedroom, 123)
    Z3Solver(1.5).solve(bedroom, 7, fixed={"garbagecan-0": (0.1365, 0.8052, 90.0)})
    assert Z3Solver(1.5).solve(bedroom, 123).placements == first.placements
