"""decision.md's data: the shipped Plan2Place's episodes (deterministic, reach guard) on `seen` and `varied`
training plans, alternating; at each step the 8 lowest-energy candidates of the policy's subset and its pick, each
with a raster of its after-state and its 9 numbers (floor.py), its energy after the step and its final energy finished greedily.
Seeded; episodes [FIRST, LAST) so that two processes can share the work. (It ran with its rasters pooled by torch's
adaptive_avg_pool2d; floor.py's numpy pooling is equal to it to 1e-13.)

    PYTHONPATH=. python app/bench/results/plan2place/grid-critic/gen.py OUT.pkl FIRST LAST
"""

from __future__ import annotations

import importlib.util
import pickle
import sys
from pathlib import Path

import numpy as np

from models.datasets import load_dataset
from models.datasets.varied import varied_plan
from models.placement.plan2place.policy import shipped_policy

sys.path.insert(0, str(Path(__file__).parent))
from floor import JUDGED, after_states  # noqa: E402

SEED = 11


def _walk():
    """lookahead-critic/gen.py's walk, loaded by path (both folders hold a gen.py)."""
    path = Path(__file__).parent.parent / "lookahead-critic" / "gen.py"
    spec = importlib.util.spec_from_file_location("lookahead_gen", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.walk


walk = _walk()


def episode(plan, rng: np.random.Generator) -> list[dict]:
    policy = shipped_policy()

    def record(ep, opts, subset, obs, a, rng):
        judged = np.array(sorted({*range(min(JUDGED, len(subset))), a}))
        rasters, nums, after = after_states(ep, opts, subset, judged, policy(obs))
        return {"plan": plan.id, "judged": judged, "policy": a, "finals": ep.judge(opts, subset[judged]),
                "energy_after": after, "rasters": rasters, "numbers": nums}

    return walk(plan, rng, record)


def plan_of(k: int, seen: list):
    """Episode k's plan: even k a `seen` training plan, odd k a `varied` training plan."""
    return seen[k // 2] if k % 2 == 0 else varied_plan(0, k)


def main(out: Path, first: int, last: int) -> int:
    seen = [r.plan for r in load_dataset("seen", "train")]
    seen = [seen[i] for i in np.random.default_rng(SEED).permutation(len(seen))]
    steps = []
    for k in range(first, last):
        steps += episode(plan_of(k, seen), np.random.default_rng([SEED, k]))
        if (k + 1) % 50 == 0:
            print(k + 1, "episodes", len(steps), "steps", flush=True)
    out.write_bytes(pickle.dumps(steps))
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])))
