"""Steps judged by look-ahead, to learn from: episodes of the shipped Plan2Place (deterministic, reach guard)
on the `seen` training plans; at each step the observation of its candidate subset and, for the judged ones
(the 8 of lowest immediate energy, the policy's pick, 2 random others of the subset), the final energy of the
episode finished greedily after each (`agent.judge`, the oracle of ../lookahead-bound). Resumable, seeded.

    PYTHONPATH=. python app/bench/results/plan2place/lookahead-critic/gen.py OUT.pkl EPISODES
"""

from __future__ import annotations

import pickle
import sys
from pathlib import Path

import numpy as np

from models.datasets import load_dataset
from models.placement.greedy import Episode
from models.placement.plan2place.features import choose_subset, observe
from models.placement.plan2place.policy import shipped_policy, shipped_weights

LOWEST, RANDOM = 8, 2
SEED = 5


def walk(plan, rng: np.random.Generator, record) -> list:
    """The shipped policy's deterministic episode with the reach guard; at each step with a legal pose, what
    `record(ep, opts, subset, obs, a, rng)` returns (`a`: the pick's index into `subset`), before the pick is placed.
    (Also afterstate-critic/gen.py's walk.)"""
    policy, use_global = shipped_policy(), shipped_weights().use_global
    ep, steps = Episode(plan), []
    while not ep.done:
        opts, pick = ep.options(), None
        if len(opts.feasible):
            subset = choose_subset(opts, rng)
            obs = observe(ep, opts, subset, use_global)
            order = np.argsort(-policy(obs), kind="stable")
            a = int(np.flatnonzero(subset == ep.guarded(opts, subset[order]))[0])
            steps.append(record(ep, opts, subset, obs, a, rng))
            pick = int(subset[a])
        ep.apply(opts, pick)
    return steps


def episode(plan, rng: np.random.Generator) -> list[dict]:
    def record(ep, opts, subset, obs, a, rng):
        rest = np.arange(LOWEST, len(subset))
        extra = rng.choice(rest, size=min(RANDOM, len(rest)), replace=False) if len(rest) else []
        judged = sorted({*range(min(LOWEST, len(subset))), a, *map(int, extra)})
        return {"plan": plan.id, "glob": obs.glob, "nodes": obs.nodes, "edges": obs.edges, "cands": obs.cands,
                "judged": np.array(judged), "finals": ep.judge(opts, subset[judged]), "policy": a}

    return walk(plan, rng, record)


def main(out: Path, episodes: int) -> int:
    plans = [r.plan for r in load_dataset("seen", "train")]
    order = np.random.default_rng(SEED).permutation(len(plans))
    done = pickle.loads(out.read_bytes()) if out.exists() else {"episodes": 0, "steps": []}
    for k in range(done["episodes"], episodes):
        done["steps"] += episode(plans[order[k % len(plans)]], np.random.default_rng([SEED, k]))
        done["episodes"] = k + 1
        if (k + 1) % 50 == 0 or k + 1 == episodes:
            out.write_bytes(pickle.dumps(done))
            print(k + 1, "episodes", len(done["steps"]), "steps", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), int(sys.argv[2])))
