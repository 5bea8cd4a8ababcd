"""The placement benchmark: any registered solver by name, n/a plans counted, the complete-runs table."""

import json
from types import SimpleNamespace

from app.bench.placement import complete_everywhere, main, pto_medians, readme_section, replot, table


def test_bench_runs_registered_solvers_and_reports_both_tables(tmp_path, capsys):
    args = SimpleNamespace(dataset="unseen_b", solvers="dfs,milp", n=2, seeds=1, budget=None, out=str(tmp_path))
    assert main(args) == 0
    text = (tmp_path / "table.md").read_text()
    assert "all runs:" in text and "placed completely" in text and "| dfs |" in text and "| milp |" in text
    assert (tmp_path / "results.json").exists() and capsys.readouterr().out.startswith("placement on")


def test_update_runs_only_the_named_solvers_again_and_refuses_other_plans(tmp_path, capsys):
    import pytest
    args = SimpleNamespace(dataset="unseen_b", solvers="dfs,milp", n=2, seeds=1, budget=None, out=str(tmp_path))
    assert main(args) == 0
    path = tmp_path / "results.json"
    stale = [{**r, "energy": -1.0} for r in json.loads(path.read_text())]  # a mark the re-run must wipe off dfs only
    path.write_text(json.dumps(stale))
    assert main(SimpleNamespace(**{**vars(args), "solvers": "dfs", "update": True})) == 0
    rows = json.loads(path.read_text())
    assert [r["solver"] for r in rows] == [r["solver"] for r in stale]
    assert {r["solver"] for r in rows if r["energy"] == -1.0} == {"milp"}
    assert "dfs re-run on" in (tmp_path / "table.md").read_text() and "| milp |" in capsys.readouterr().out
    before = path.read_text()
    with pytest.raises(SystemExit, match="--n 3 --seeds 1"):
        main(SimpleNamespace(**{**vars(args), "n": 3, "update": True}))
    with pytest.raises(SystemExit, match="no stored run"):
        main(SimpleNamespace(**{**vars(args), "out": str(tmp_path / "none"), "update": True}))
    assert path.read_text() == before


def test_the_solvers_take_turns_run_by_run_and_the_rows_come_back_solver_by_solver():
    from app.batch.executors import InProcess
    from app.bench.placement import run, turns

    class Recording(InProcess):
        def run(self, fn, items):
            self.handed = [(item[1], item[2], item[3].id) for item in items]
            yield from reversed(list(super().run(fn, items)))  # finished in another order than handed out

    assert turns(2, 3) == [0, 3, 1, 4, 2, 5]
    executor = Recording()
    rows = run("unseen_b", ["dfs", "milp"], 2, 2, None, executor)
    assert [h[0] for h in executor.handed] == ["dfs", "milp"] * 4
    assert [(r["solver"], r["seed"], r["plan"]) for r in rows] == sorted(executor.handed, key=lambda h: h[0] != "dfs")
    assert len(set(executor.handed)) == 8  # each run once


def test_na_values_are_left_out_and_counted():
    row = dict(cnt=1.0, sr=None, nav=1.0, key_nav=None, oob=0.0, pto=0.1, collisions=0, constraint_satisfaction=1.0,
               realism=None, energy=0.0, complete=True)
    rows = [{**row, "solver": "a", "seed": 0, "plan": "p"}, {**row, "solver": "a", "seed": 0, "plan": "q", "sr": 1.0},
            {**row, "solver": "b", "seed": 0, "plan": "p", "complete": False}]
    text = table(rows, ["a"])
    assert "| 100.00 +- 0.00 |" in text and "1 / 2 of 2" in text
    assert complete_everywhere(rows, ["a", "b"]) == set()
    assert complete_everywhere(rows, ["a"]) == {("p", 0), ("q", 0)}


def test_plan2place_bench_chooses_checkpoints_on_varied_validation_plans(tmp_path, capsys):
    from app.bench.plan2place import main as plan2place_main
    from models.placement.plan2place.policy import SHIPPED
    args = SimpleNamespace(dataset="varied", n=2, seeds=1, runs=f"models/{SHIPPED}", out=str(tmp_path))
    assert plan2place_main(args) == 0
    text = (tmp_path / "plan2place.md").read_text()
    assert "2 `varied` plans" in text and "| greedy |" in text and "| plan2place (" in text
    assert "| plan2place (2880 ep) - greedy |" in text and "| plan2place (2880 ep) - plan2place_untrained |" in text
    assert "| plan2place (2880 ep), no repair - plan2place_untrained, no repair |" in text  # the placers alone
    rows = json.loads((tmp_path / "results.json").read_text())
    assert {(r["solver"], r["seed"]) for r in rows} >= {("greedy", 0), ("plan2place (2880 ep)", 0)}


def test_a_paired_lead_is_called_only_when_its_interval_is_clear_of_zero():
    import numpy as np
    from app.bench.paired import cell, interval, paired
    rows = [{"solver": s, "plan": p, "seed": k, "energy": e + (0.5 if s == "b" else 0.0) + 0.01 * k}
            for s in ("a", "b") for p, e in (("p", 1.0), ("q", 2.0), ("r", 0.0)) for k in range(2)]
    diffs = paired(rows + [{"solver": "a", "plan": "s", "seed": 0, "energy": None}], "energy", "a", "b")
    assert diffs == {"p": [-0.5, -0.5], "q": [-0.5, -0.5], "r": [-0.5, -0.5]}  # no pair for a missing value
    mean, lo, hi = interval(diffs, np.random.default_rng(0))
    assert mean == lo == hi == -0.5 and cell(mean, lo, hi, higher_is_better=False).startswith("**")
    assert cell(mean, lo, hi, higher_is_better=True).startswith("_")
    noisy = {"p": [-1.0], "q": [1.2], "r": [-0.1]}
    assert not cell(*interval(noisy, np.random.default_rng(0)), higher_is_better=False).startswith(("**", "_"))
    assert np.isnan(interval({}, np.random.default_rng(0))[0])  # nothing to compare earns no lead
    tiny = -2e-17  # two float sums of one layout in another order: shown -0.000, not a lead
    assert not cell(tiny, tiny, tiny, higher_is_better=False, digits=3).startswith(("**", "_"))
    assert cell(-0.001, -0.001, -0.001, higher_is_better=False, digits=3).startswith("**")


def test_pto_medians_come_from_the_stored_runs(tmp_path):
    runs = [{"solver": s, "pto": t} for s, ts in (("human", [0.0]), ("dfs", [0.001, 0.002, 0.009]),
                                                   ("plan2place", [0.003, 0.004, 0.100])) for t in ts]
    (tmp_path / "placement-seen").mkdir()
    (tmp_path / "placement-seen" / "results.json").write_text(json.dumps(runs))
    table = pto_medians(tmp_path)
    assert "| dfs | 2.0 (1.00 x dfs) |" in table and "| plan2place | 4.0 (2.00 x dfs) |" in table
    assert "human" not in table  # the people's arrangement took no time to place


def test_readme_section_shows_each_stored_set_with_its_plot_and_plots_remake_from_stored_runs(tmp_path):
    out = tmp_path / "placement-unseen_b"
    assert main(SimpleNamespace(dataset="unseen_b", solvers="dfs", n=2, seeds=1, budget=None, out=str(out))) == 0
    plot = out / "metric_distributions.png"
    plot.unlink()
    assert replot(tmp_path) == [out / "time_per_scene.png", plot] and plot.stat().st_size > 1000
    section = readme_section(tmp_path)
    assert "**unseen_b**" in section and "| dfs |" in section and "**seen**" not in section
    assert "(app/bench/results/placement-unseen_b/metric_distributions.png)" in section


def test_variants_alternate_run_by_run_and_the_value_they_change_is_put_back():
    """`alternating` solves each (plan, seed) under both variants, in turns, with the variant's value in place while it
    solves; `variant_rows` counts the layouts a variant left unchanged (both here, the two variants polishing alike)."""
    import itertools
    from unittest import mock

    import models.placement.repair as repair
    from app.bench.paired import alternating, variant_rows
    from models.datasets import load_dataset
    from models.placement import exact_finish

    shipped, called = repair.polish, []

    def variant(name, moves):
        def polish(ep, observer=None):
            called.append(name)
            return shipped(ep, observer) if moves else []
        return polish

    plans = [r.plan for r in load_dataset("dense") if r.plan.id == "dense-00074"]
    metrics = (("constraint_satisfaction", 100, True, 2), ("pto_ms", 1, False, 2))
    rows = alternating({"dense": (plans, range(2))}, repair, "polish",
                       {"a": variant("a", True), "b": variant("b", True)}, metrics, placers=("greedy",))
    assert repair.polish is shipped
    assert [r["solver"] for r in rows] == ["a", "b", "b", "a"]
    assert [name for name, _ in itertools.groupby(called)] == ["a", "b", "a"]  # a solve may polish more than once
    assert all(r["set"] == "dense" and r["plan"] == "dense-00074" and r["pto_ms"] > 0 for r in rows)
    assert "(2 runs, 2 layouts unchanged)" in variant_rows(rows, "a", "b", metrics, placers=("greedy",))[0]
    three = rows + [{**r, "solver": "c"} for r in rows if r["solver"] == "a"]  # a run of three variants: still 2 runs
    assert "(2 runs, 2 layouts unchanged)" in variant_rows(three, "a", "c", metrics, placers=("greedy",))[0]
    with mock.patch.object(exact_finish, "MAX_OBJECTS", 0):  # (else Z3's finish may end both at one layout)
        off = alternating({"dense": (plans, range(1))}, repair, "polish", {"off": variant("off", False), "on": shipped},
                          metrics, placers=("greedy",))
    assert off[0]["layout"] != off[1]["layout"]  # the polish moves something on this plan: layouts tell it
    assert "(1 runs, 0 layouts unchanged)" in variant_rows(off, "off", "on", metrics, placers=("greedy",))[0]


def test_a_gate_report_pairs_the_variants_and_shows_each_placers_p50_change():
    from app.bench.gates import METRICS, variant_report

    def row(solver, plan, ms, cnt):
        return {"set": "dense", "placer": "greedy", "solver": solver, "plan": plan, "seed": 0, "layout": plan + solver,
                "cnt": cnt, "key_nav": 1.0, "constraint_satisfaction": 0.5, "energy": 1.0, "realism": 0.5,
                "pto_ms": ms}
    rows = [row("off", "p1", 10.0, 1.0), row("on", "p1", 15.0, 0.9), row("off", "p2", 20.0, 1.0),
            row("on", "p2", 25.0, 0.8)]
    report = variant_report("the change", "made-up plans", rows, ("off", "on"), ("greedy",), METRICS)
    assert report.startswith("the change - without, made-up plans, mean over the same (plan, seed) runs")
    assert "| dense / greedy (2 runs, 0 layouts unchanged) | _-15.00" in report  # CNT falls: worse
    assert "- dense / greedy: 15.00 -> 20.00 (+33.3 %)" in report


def test_a_gates_pooled_constraints_pair_each_plan_of_every_set_as_one_unit():
    """The pooled condition of a gate's rule: the second variant minus the first over the runs of all sets, a plan
    of one set never paired with the plan of the same name in another."""
    from app.bench.gates import pooled_constraints

    def row(ds, solver, plan, met):
        return {"set": ds, "placer": "plan2place", "solver": solver, "plan": plan, "seed": 0,
                "constraint_satisfaction": met}
    gain = {"seen": 0.1, "human": 0.3}
    rows = [row(ds, v, f"p{k}", 0.5 + (gain[ds] if v == "with" else 0.0)) for ds in gain
            for k in range(4) for v in ("without", "with")]
    line = pooled_constraints(rows, "plan2place", {"without": 0, "with": 1})
    assert line.startswith("- plan2place: **+20.00 [") and "[+20.00, +20.00]" not in line  # 8 units, not 4 mixed
    rows.append(row("human", "with", "p9", 0.1))  # a run of one variant alone is no pair
    assert pooled_constraints(rows, "plan2place", {"without": 0, "with": 1}) == line
    assert pooled_constraints(rows, "plan2place", {"with": 1, "without": 0}).startswith("- plan2place: _-20.00")


def test_the_finish_runs_the_probes_replay_are_the_stored_small_rooms_with_a_constraint_broken():
    """`finish_runs`: the stored `human` Plan2Place runs in which the exact finish of a small room may run, as plans
    (not ids) with their seeds; a run that meets every constraint is not one, and one of more objects is a larger room's."""
    from pathlib import Path

    from app.bench.gates import finish_runs
    from models.placement.exact_finish import MAX_OBJECTS, MIN_MET

    rows = json.loads((Path(__file__).parents[1] / "app/bench/results/placement-human/results.json").read_text())
    mine = {(r["plan"], r["seed"]): r for r in rows if r["solver"] == "plan2place"}
    runs = finish_runs("human")
    assert runs and len({(p.id, s) for p, s in runs}) == len(runs)
    for plan, seed in runs:
        r = mine[(plan.id, seed)]
        assert len(plan.objects) == r["n_objects"] <= MAX_OBJECTS and MIN_MET <= r["constraint_satisfaction"] < 1
    larger = finish_runs("human", small=False)
    for plan, seed in larger:
        r = mine[(plan.id, seed)]
        assert len(plan.objects) == r["n_objects"] > MAX_OBJECTS and MIN_MET <= r["constraint_satisfaction"] < 1
    broken = [r for r in mine.values() if not r["unplaced"] and MIN_MET <= r["constraint_satisfaction"] < 1]
    assert len(runs) == sum(r["n_objects"] <= MAX_OBJECTS for r in broken) and larger
    assert len(runs) + len(larger) == len(broken) < len(mine)  # every such run is one or the other; the rest neither
