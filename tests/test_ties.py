"""Ties between poses of equal energy do not hang on the last bits of a float sum: a change of one unit in the last
place of every candidate's energy total (another order of summation, another CPU's maths) leaves the layouts of the
step-wise placers and their repairs as they were (models.placement.ties)."""

import numpy as np
import pytest

from models.datasets import load_dataset
from models.energy.vectorised import CandidateEnergy
from models.placement import get_solver
from models.placement.ties import RESOLUTION, steady


def _one_ulp_off(monkeypatch, seed: int) -> None:
    """From now on every energy scoring moves each candidate's total one unit in the last place up, down or not."""
    score, rng = CandidateEnergy.score, np.random.default_rng(seed)

    def off(self, *args, **kwargs):
        terms = score(self, *args, **kwargs)
        way = rng.integers(-1, 2, len(terms["total"]))
        toward = np.where(way > 0, np.inf, -np.inf)
        terms["total"] = np.where(way == 0, terms["total"], np.nextafter(terms["total"], toward))
        return terms

    monkeypatch.setattr(CandidateEnergy, "score", off)


@pytest.mark.parametrize("solver", ["greedy", "plan2place"])
def test_a_last_bit_change_of_the_energies_changes_no_layout(monkeypatch, solver):
    plans = [r.plan for r in load_dataset("seen", "validation")[:40:10]]
    poses = lambda layout: sorted((p.id, p.x, p.z, p.rotation) for p in layout.placements)  # noqa: E731
    before = [poses(get_solver(solver).solve(plan, seed=1)) for plan in plans]
    _one_ulp_off(monkeypatch, seed=0)
    assert [poses(get_solver(solver).solve(plan, seed=1)) for plan in plans] == before


def test_steady_ties_energies_a_float_rounding_apart_and_keeps_larger_gaps():
    e = np.array([0.3, 0.1 + 0.2, 0.3 + 2 * RESOLUTION])  # 0.1 + 0.2 is 0.30000000000000004
    assert e[0] != e[1] and steady(e)[0] == steady(e)[1] < steady(e)[2]
    assert int(np.argmin(steady(e[::-1][1:]))) == 0  # the tie goes to the first
