"""The default semantic scorer: logistic regression on the arrangement statistics, learned from the
iTHOR rooms (human layouts, label 1) against perturbed copies (positions shuffled, objects scattered,
turned; label 0). A stand-in for the paper's VLM judge, not a VLM.

    python -m models.semantic.learned    # retrains models/weights/semantic/scorer.json (seeded)
"""

from __future__ import annotations

import json
from functools import cache
from importlib import resources
from pathlib import Path

import numpy as np

from models.semantic.base import FEATURES, LayoutItem, SemanticScore, arrangement_features

OUT = Path(__file__).resolve().parents[1] / "weights" / "semantic" / "scorer.json"
HELD_OUT = 4  # every 4th iTHOR room is held out for the accuracy figure


class LearnedScorer:
    dim = len(FEATURES)

    def __init__(self, weights: dict | None = None):
        w = weights or json.loads(resources.files("models").joinpath("weights/semantic/scorer.json").read_text())
        self.mean, self.std = np.array(w["mean"], np.float32), np.array(w["std"], np.float32)
        self.coef, self.bias = np.array(w["coef"], np.float32), float(w["bias"])

    def score(self, room_type: str, width: float, depth: float, items: list[LayoutItem]) -> SemanticScore:
        h = (arrangement_features(room_type, width, depth, items) - self.mean) / self.std
        return SemanticScore(h.astype(np.float32), float(1 / (1 + np.exp(-(h @ self.coef + self.bias)))))


@cache
def default_scorer() -> LearnedScorer:
    return LearnedScorer()


def ithor_layouts() -> list[tuple[str, float, float, list[LayoutItem]]]:
    """The iTHOR rooms as (room type, width, depth, floor objects) with the room's corner at the origin."""
    from models.world import catalogue
    from models.world.catalogue import ithor_scenes
    cat = catalogue()
    floor = {n for n, t in cat.types.items() if t.on_floor and not t.pickupable}
    out = []
    for scene in ithor_scenes():
        objs = [o for o in scene["objects"] if o["type"] != "Floor"]
        x0 = min(o["x"] - o["size"][0] / 2 for o in objs)
        z0 = min(o["z"] - o["size"][2] / 2 for o in objs)
        x1 = max(o["x"] + o["size"][0] / 2 for o in objs)
        z1 = max(o["z"] + o["size"][2] / 2 for o in objs)
        items = [LayoutItem(o["type"], o["x"] - x0, o["z"] - z0, float(o["rotation"]), o["size"][0], o["size"][2])
                 for o in objs if o["type"] in floor and not o["parents"]]
        if len(items) >= 2:
            out.append((scene["room_type"], x1 - x0, z1 - z0, items))
    return out


def perturb(rng: np.random.Generator, width: float, depth: float, items: list[LayoutItem]) -> list[LayoutItem]:
    kind = rng.integers(3)
    if kind == 0:  # positions shuffled among the objects
        perm = rng.permutation(len(items))
        return [LayoutItem(it.type, items[j].x, items[j].z, it.rotation, it.width, it.depth) for it, j in zip(items, perm)]
    if kind == 1:  # scattered uniformly, random right-angle turns
        return [LayoutItem(it.type, rng.uniform(0, width), rng.uniform(0, depth), float(rng.integers(4) * 90),
                           it.width, it.depth) for it in items]
    return [LayoutItem(it.type, it.x, it.z, (it.rotation + float(rng.integers(1, 4) * 90)) % 360, it.width, it.depth)
            for it in items]


def train(seed: int = 0, copies: int = 6, steps: int = 3000) -> tuple[dict, dict]:
    rng = np.random.default_rng(seed)
    rows, labels, test = [], [], []
    for k, (room, w, d, items) in enumerate(ithor_layouts()):
        held = k % HELD_OUT == 0
        rows.append(arrangement_features(room, w, d, items))
        labels.append(1)
        test.append(held)
        for _ in range(copies):
            rows.append(arrangement_features(room, w, d, perturb(rng, w, d, items)))
            labels.append(0)
            test.append(held)
    x, y, test = np.array(rows, float), np.array(labels, float), np.array(test)
    mean, std = x[~test].mean(0), x[~test].std(0) + 1e-6
    xs = (x - mean) / std
    coef, bias = np.zeros(x.shape[1]), 0.0
    pos_w = (y[~test] == 0).sum() / max((y[~test] == 1).sum(), 1)  # balance the classes
    sw = np.where(y == 1, pos_w, 1.0)
    for _ in range(steps):
        p = 1 / (1 + np.exp(-(xs[~test] @ coef + bias)))
        g = (p - y[~test]) * sw[~test]
        coef -= 0.1 * (xs[~test].T @ g / len(g) + 1e-3 * coef)
        bias -= 0.1 * g.mean()
    p = 1 / (1 + np.exp(-(xs @ coef + bias)))
    acc = lambda m: float((((p > 0.5) == (y == 1))[m]).mean())  # noqa: E731
    pos, neg = p[test & (y == 1)], p[test & (y == 0)]
    auc = float((pos[:, None] > neg[None, :]).mean())
    weights = {"features": list(FEATURES), "mean": mean.tolist(), "std": std.tolist(), "coef": coef.tolist(),
               "bias": bias, "seed": seed}
    return weights, {"train_accuracy": acc(~test), "held_out_accuracy": acc(test), "held_out_auc": auc,
                     "held_out_rooms": int((test & (y == 1)).sum())}


if __name__ == "__main__":
    weights, report = train()
    OUT.write_text(json.dumps({**weights, "report": report}, indent=1) + "\n")
    print(f"wrote {OUT}: {report}")
