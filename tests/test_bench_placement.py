"""The placement benchmark: any registered solver by name, n/a plans counted, the complete-runs table."""

from types import SimpleNamespace

from app.bench.placement import complete_everywhere, main, table


def test_bench_runs_registered_solvers_and_reports_both_tables(tmp_path, capsys):
    args = SimpleNamespace(dataset="unseen_b", solvers="dfs,milp", n=2, seeds=1, budget=None, out=str(tmp_path))
    assert main(args) == 0
    text = (tmp_path / "table.md").read_text()
    assert "all runs:" in text and "placed completely" in text and "| dfs |" in text and "| milp |" in text
    assert (tmp_path / "results.json").exists() and capsys.readouterr().out.startswith("placement on")


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
