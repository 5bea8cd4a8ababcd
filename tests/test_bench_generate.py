"""The generate benches compare placers: DFS (the default before) and the default solver unless told."""

from types import SimpleNamespace

from app.bench import generate
from models.placement import DEFAULT_SOLVER


def test_placers_default_to_dfs_and_the_default_solver():
    assert generate.placers(SimpleNamespace(solvers=None)) == ["dfs", DEFAULT_SOLVER]
    assert generate.placers(SimpleNamespace(solvers="greedy, greedy,dfs")) == ["greedy", "dfs"]


def test_generate_bench_prints_one_block_per_placer(capsys):
    assert generate.main(SimpleNamespace(n=2, solvers="dfs,plan2place", room_type=None)) == 0
    out = capsys.readouterr().out
    for name in ("dfs", "plan2place"):
        assert f"instructions (0 unparseable skipped), {name} placer" in out
    assert out.count("Key_NAV from doorway") == 2 and "unplaced objects 0 of" in out
