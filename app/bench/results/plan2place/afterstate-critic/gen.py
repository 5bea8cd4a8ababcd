"""After-states judged by look-ahead (decision.md): the shipped Plan2Place's episodes (deterministic, reach guard) on
`seen` training plans; at each step the 8 lowest-energy candidates of its subset and its pick, each with its
after-state observation (the layout with it placed, the next object flagged; None when the episode ends with it or
the next object has no legal pose), its energy after the step and its final energy finished greedily. Seeded.

    PYTHONPATH=. python app/bench/results/plan2place/afterstate-critic/gen.py OUT.pkl FIRST LAST   # plans [FIRST, LAST)
"""

from __future__ import annotations

import pickle
import sys
from pathlib import Path

import numpy as np

from models.datasets import load_dataset
from models.placement.greedy import Episode
from models.placement.plan2place.features import observe
from models.placement.plan2place.policy import shipped_weights


def _lookahead_gen():
    """lookahead-critic/gen.py, loaded under a name of its own (this file is gen.py too)."""
    import importlib.util
    path = Path(__file__).parent.parent / "lookahead-critic" / "gen.py"
    spec = importlib.util.spec_from_file_location("lookahead_gen", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


walk = _lookahead_gen().walk

LOWEST = 8
SEED = 9


def after_state(ep: Episode, opts, pick: int, use_global: bool):
    """(observation of the step after placing `pick`, or None; the energy after the step)."""
    twin = ep.fork()
    twin.apply(opts, pick)
    if twin.done:
        return None, twin.energy
    nxt = twin.options()
    if not len(nxt.feasible):
        return None, twin.energy
    return observe(twin, nxt, np.arange(1), use_global), twin.energy


def episode(plan, rng: np.random.Generator) -> list[dict]:
    use_global = shipped_weights().use_global

    def record(ep, opts, subset, obs, a, rng):
        judged = sorted({*range(min(LOWEST, len(subset))), a})
        afters = [after_state(ep, opts, int(subset[j]), use_global) for j in judged]
        return {"plan": plan.id, "before": ep.energy, "judged": np.array(judged),
                "finals": ep.judge(opts, subset[judged]), "after": [o for o, _ in afters],
                "energy_after": np.array([e for _, e in afters]), "policy": a}

    return walk(plan, rng, record)


def main(out: Path, first: int, last: int) -> int:
    plans = [r.plan for r in load_dataset("seen", "train")]
    order = np.random.default_rng(SEED).permutation(len(plans))
    steps = []
    for k in range(first, last):
        steps += episode(plans[order[k]], np.random.default_rng([SEED, k]))
        if (k + 1) % 50 == 0:
            print(k + 1, "episodes", len(steps), "steps", flush=True)
    out.write_bytes(pickle.dumps(steps))
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])))
