"""The incremental set-up of the vectorised energy (CandidateEnergy.after) equals a fresh one, step by step."""

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
