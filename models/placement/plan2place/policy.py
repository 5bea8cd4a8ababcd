"""Plan2Place at inference, without torch: the actor's logits in float32 numpy (`NumpyPolicy`), the loop
that places a plan with them (`place`), and the shipped weights as a numpy archive.

The solver thus starts without importing torch and torch_geometric (about 7 s on this CPU, against
about 1 s for the rest of `h3ds place`); training (`agent`, `network`) still uses torch and exports here.
"""

from __future__ import annotations

import io
import json
from collections.abc import Callable
from dataclasses import asdict, dataclass
from functools import cache
from importlib import resources
from pathlib import Path

import numpy as np

from models.placement.base import Fixed, StepObserver
from models.placement.greedy import Episode, Options, place_stepwise
from models.placement.plan2place.features import ENERGY_GAP, Observation, choose_subset, observe
from models.values import ConstraintPlan

SHIPPED = "weights/plan2place/plan2place.npz"

Policy = Callable[[Observation], np.ndarray]  # observation -> logits over its candidates


@dataclass(frozen=True)
class NetConfig:
    hidden: int = 128
    fusion: str = "cross"  # cross | self | concat
    sff: bool = True
    semantic_dim: int = 8
    heads: int = 4
    prior_temp: float = 0.05  # logits += -(energy - lowest energy) / prior_temp; 0: no energy prior

    def as_dict(self) -> dict:
        return asdict(self)


@dataclass
class Weights:
    """An exported network: its parameters by state-dict name, the training configuration, the episodes."""

    arrays: dict[str, np.ndarray]
    config: dict
    episode: int

    @property
    def net(self) -> NetConfig:
        return NetConfig(**self.config["net"])

    @property
    def use_global(self) -> bool:
        return self.config.get("use_global", True)

    def save(self, path: Path) -> None:
        """float16 parameters (a few MB) and the configuration as JSON, in one .npz."""
        meta = json.dumps({"config": self.config, "episode": self.episode})
        np.savez_compressed(path, __meta__=np.array(meta), **{k: v.astype(np.float16) for k, v in self.arrays.items()})

    @classmethod
    def load(cls, data: bytes | Path) -> Weights:
        with np.load(io.BytesIO(data) if isinstance(data, bytes) else data) as z:
            meta = json.loads(str(z["__meta__"]))
            arrays = {k: z[k].astype(np.float32) for k in z.files if k != "__meta__"}
        return cls(arrays, meta["config"], meta["episode"])


class NumpyPolicy:
    """The actor's logits of the network (cross-attention fusion) in float32 numpy: what the solver runs per
    step. Torch spends ~10-30 us of dispatch per small op on this CPU, about 1 ms per step for ~40 ops; the
    same arithmetic in numpy takes a fraction of that. It equals `Plan2PlaceNet.policy` up to float32
    rounding (summation order of the matrix products; tested: same argmax, logits within 1e-4)."""

    def __init__(self, w: dict[str, np.ndarray], cfg: NetConfig):
        if cfg.fusion != "cross":
            raise ValueError("NumpyPolicy implements the cross-attention fusion only")
        h = cfg.hidden
        self.heads, self.prior_temp, self.h = cfg.heads, cfg.prior_temp, h
        t = lambda k: np.ascontiguousarray(w[k].T)  # noqa: E731  (x @ W.T as x @ Wt)
        self.g0, self.gb0, self.g2, self.gb2 = t("glob.0.weight"), w["glob.0.bias"], t("glob.2.weight"), w["glob.2.bias"]
        self.s1l, self.s1b, self.s1r = t("sage1.lin_l.weight"), w["sage1.lin_l.bias"], t("sage1.lin_r.weight")
        self.s2l, self.s2b, self.s2r = t("sage2.lin_l.weight"), w["sage2.lin_l.bias"], t("sage2.lin_r.weight")
        wi, bi = w["attn.in_proj_weight"], w["attn.in_proj_bias"]
        self.wq, self.bq = np.ascontiguousarray(wi[:h].T), bi[:h]
        self.wkv, self.bkv = np.ascontiguousarray(wi[h:].T), bi[h:]
        self.wo, self.bo = t("attn.out_proj.weight"), w["attn.out_proj.bias"]
        self.ln_w, self.ln_b = w["ffn.0.weight"], w["ffn.0.bias"]
        self.f1, self.fb1, self.f3, self.fb3 = t("ffn.1.weight"), w["ffn.1.bias"], t("ffn.3.weight"), w["ffn.3.bias"]
        self.c0, self.cb0 = t("cand.0.weight"), w["cand.0.bias"]
        a0 = w["actor.0.weight"]
        self.a_state, self.a_cand, self.ab0 = np.ascontiguousarray(a0[:, :h].T), np.ascontiguousarray(a0[:, h:].T), \
            w["actor.0.bias"]
        self.a2, self.ab2 = w["actor.2.weight"][0], w["actor.2.bias"][0]

    def __call__(self, obs: Observation) -> np.ndarray:
        relu = lambda v: np.maximum(v, np.float32(0))  # noqa: E731
        hg = relu(obs.glob @ self.g0 + self.gb0) @ self.g2 + self.gb2
        x = obs.nodes
        n = len(x)
        adj = np.bincount(obs.edges[1] * n + obs.edges[0], minlength=n * n).reshape(n, n).astype(np.float32)
        adj /= np.maximum(adj.sum(1, keepdims=True), np.float32(1))  # row i: mean over i's in-neighbours

        def sage(v, wl, bl, wr):
            return (adj @ v) @ wl + bl + v @ wr

        hl = relu(sage(relu(sage(x, self.s1l, self.s1b, self.s1r)), self.s2l, self.s2b, self.s2r))
        kv = np.concatenate([hl.mean(0, keepdims=True), hl]) @ self.wkv + self.bkv  # (V+1, 2h)
        h, nh = self.h, self.heads
        hd = h // nh
        q = ((hg @ self.wq + self.bq) / np.float32(np.sqrt(hd))).reshape(nh, hd)
        k, v = kv[:, :h].reshape(-1, nh, hd), kv[:, h:].reshape(-1, nh, hd)
        s = np.einsum("hd,lhd->hl", q, k)
        s = np.exp(s - s.max(1, keepdims=True))
        s /= s.sum(1, keepdims=True)
        att = np.einsum("hl,lhd->hd", s, v).reshape(h) @ self.wo + self.bo
        fused = att + hg
        mu = fused.mean()
        var = ((fused - mu) ** 2).mean()
        ln = (fused - mu) / np.sqrt(var + np.float32(1e-5)) * self.ln_w + self.ln_b
        f = fused + relu(ln @ self.f1 + self.fb1) @ self.f3 + self.fb3
        c = relu(obs.cands @ self.c0 + self.cb0)
        logits = relu(c @ self.a_cand + (f @ self.a_state + self.ab0)) @ self.a2 + self.ab2
        if self.prior_temp > 0:
            logits = logits - obs.cands[:, ENERGY_GAP] / np.float32(self.prior_temp)
        return logits


@cache
def shipped_weights() -> Weights:
    return Weights.load(resources.files("models").joinpath(SHIPPED).read_bytes())


@cache
def shipped_policy() -> NumpyPolicy:
    w = shipped_weights()
    return NumpyPolicy(w.arrays, w.net)


def place(policy: Policy, plan: ConstraintPlan, rng: np.random.Generator, use_global: bool = True,
          fixed: Fixed | None = None, observer: StepObserver | None = None, repair: bool = True,
          guard: bool = True, keep_reach: bool = True, exact: bool = False) -> Episode:
    """One deterministic episode: each object at the most probable of its candidates (fixed poses kept; with
    `guard`, the most probable that walls off no task object, `Episode.guarded`), then, with `repair`, the
    repairs (models.placement.repair; `keep_reach`, `exact`: `place_stepwise`'s)."""
    def choose(ep: Episode, opts: Options, rng: np.random.Generator) -> tuple[int, np.ndarray, str]:
        if opts.obj.id in ep.problem.fixed:
            return 0, np.ones(1), ""
        subset = choose_subset(opts, rng)
        logits = policy(observe(ep, opts, subset, use_global))
        a = int(np.argmax(logits))
        p = np.exp(logits - logits[a])
        probs = np.zeros(len(opts.feasible))
        probs[subset] = p / p.sum()
        pick = int(subset[a])
        if guard and pick != (guarded := ep.guarded(opts, subset[np.argsort(-logits, kind="stable")])):
            return guarded, probs, ep.walls_off
        return pick, probs, ""

    return place_stepwise(plan, rng, choose, fixed, observer, repair, keep_reach, exact)
