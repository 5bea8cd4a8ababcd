"""The agent's state: the global vector s_g, the local relational graph and the candidate features.

- s_g (5): relations of the next object / 4, relations of the plan per object / 4, the next object's
  footprint / room area, share of objects still to place, occupied floor share.
- Graph: a node per plan object (placed, the next one, and those still to come): size ratios, position,
  orientation, flags, a MiniLM embedding of the type (stand-in for CLIP); edges for every constraint
  pair and from every placed object to the next one, with distance, direction, alignment and a
  constraint flag, averaged onto the nodes (SAGEConv takes no edge attributes).
- Candidates (K, C): the top-K feasible poses by immediate energy (plus a few random feasible ones),
  each with its position, rotation, wall distance and per-step energy terms.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from models.placement.greedy import Episode, Options
from models.placement.plan2place.type_embedding import EMBED_DIM, embed

TOP_K = 40
RANDOM_K = 8
TERMS = ("rel", "collision", "oob", "nav", "aff")
GLOBAL_DIM = 5
EDGE_DIM = 5
NODE_DIM = 10 + EMBED_DIM + EDGE_DIM
CAND_DIM = 9 + len(TERMS) + 2
ENERGY_GAP = 9 + len(TERMS)  # column of a candidate's per-step energy above the best candidate's


@dataclass
class Observation:
    glob: np.ndarray  # (GLOBAL_DIM,)
    nodes: np.ndarray  # (V, NODE_DIM)
    edges: np.ndarray  # (2, E) int64
    cands: np.ndarray  # (K, CAND_DIM)
    subset: np.ndarray  # (K,) indices into opts.feasible


def choose_subset(opts: Options, rng: np.random.Generator) -> np.ndarray:
    m = len(opts.feasible)
    total = opts.terms["total"] + rng.uniform(0, 1e-9, m)
    order = np.argsort(total)
    top = order[:TOP_K]
    rest = order[TOP_K:]
    extra = rng.choice(rest, size=min(RANDOM_K, len(rest)), replace=False) if len(rest) else np.zeros(0, int)
    return np.concatenate([top, extra]).astype(np.int64)


class _Static:
    """What `observe` needs that does not change during an episode (the plan's objects, their order and
    constraints): node features that do not depend on poses, the constraint pairs and their flags."""

    def __init__(self, ep: Episode):
        plan, room = ep.problem.plan, ep.problem.plan.room
        cons = ep.problem.constraints.objects
        objs = ep.order
        self.W, self.D = room.width, room.depth
        self.n_rel = sum(len(c.relations) for c in cons.values())
        self.n_plan = max(len(plan.objects), 1)
        self.index = {o.id: k for k, o in enumerate(objs)}
        nodes = np.zeros((len(objs), NODE_DIM), np.float32)
        for k, o in enumerate(objs):
            nodes[k, [0, 1, 8, 9]] = [o.size.x / self.W, o.size.z / self.D, o.is_task, ep.problem.clearance.get(o.id, 0.0)]
            nodes[k, 10:10 + EMBED_DIM] = embed(o.type)
        self.nodes = nodes
        index = self.index
        self.pairs = {(index[a], index[c.target]) for a, oc in cons.items() if a in index
                      for c in oc.relations if c.target in index}
        self.constrained = np.zeros((len(objs), len(objs)), bool)  # a has a relation to b
        for a, b in self.pairs:
            self.constrained[a, b] = True


def observe(ep: Episode, opts: Options, subset: np.ndarray, use_global: bool = True) -> Observation:
    st = ep.__dict__.get("_observe_static")
    if st is None:
        st = ep.__dict__["_observe_static"] = _Static(ep)
    W, D = st.W, st.D
    area = W * D
    cons = ep.problem.constraints.objects
    obj = opts.obj
    occupied = sum(p.width * p.depth for p in ep.placed)
    glob = np.array([len(cons[obj.id].relations) / 4, st.n_rel / st.n_plan / 4,
                     obj.size.x * obj.size.z / area, (len(ep.order) - ep.i) / max(len(ep.order), 1),
                     occupied / area], np.float32)
    if not use_global:
        glob = np.zeros_like(glob)

    n = len(ep.order)
    index = st.index
    placed = [p for p in ep.placed if p.id in index]
    rows = np.array([index[p.id] for p in placed], np.intp)
    px, pz, prot = np.zeros(n), np.zeros(n), np.zeros(n)  # poses of the placed nodes (0 for the others)
    is_placed = np.zeros(n, bool)
    if len(placed):
        px[rows], pz[rows] = [p.x for p in placed], [p.z for p in placed]
        prot[rows] = [p.rotation for p in placed]
        is_placed[rows] = True
    nodes = st.nodes.copy()
    r = np.radians(prot[rows])
    nodes[rows, 2], nodes[rows, 3] = px[rows] / W, pz[rows] / D
    nodes[rows, 4], nodes[rows, 5], nodes[rows, 6] = np.sin(r), np.cos(r), 1.0
    nodes[index[obj.id], 7] = 1.0
    nxt = index[obj.id]
    pairs = st.pairs | {(int(a), nxt) for a in rows}
    pairs = sorted(pairs | {(b, a) for a, b in pairs})
    edges = np.array(pairs, np.int64).T.reshape(2, -1)
    if edges.shape[1]:
        a, b = edges
        feat = np.zeros((edges.shape[1], EDGE_DIM), np.float32)
        both = is_placed[a] & is_placed[b]
        dx, dz = px[b[both]] - px[a[both]], pz[b[both]] - pz[a[both]]
        dist = np.hypot(dx, dz)
        feat[both, 0] = dist / np.hypot(W, D)
        feat[both, 1], feat[both, 2] = dx / (dist + 1e-6), dz / (dist + 1e-6)
        feat[both, 3] = np.abs(np.cos(np.radians(prot[a[both]] - prot[b[both]])))
        feat[:, 4] = st.constrained[a, b]
        sums = np.zeros((n, EDGE_DIM), np.float32)
        np.add.at(sums, b, feat)
        counts = np.bincount(b, minlength=n)[:, None]
        nodes[:, 10 + EMBED_DIM:] = sums / np.maximum(counts, 1)

    c = opts.cands[opts.feasible[subset]]
    w_eff = np.where(c[:, 2] % 180 == 0, obj.size.x, obj.size.z)
    d_eff = np.where(c[:, 2] % 180 == 0, obj.size.z, obj.size.x)
    wall = np.minimum.reduce([c[:, 0] - w_eff / 2, c[:, 1] - d_eff / 2, W - c[:, 0] - w_eff / 2, D - c[:, 1] - d_eff / 2])
    rot = np.eye(4, dtype=np.float32)[(c[:, 2] // 90).astype(int) % 4]
    total = opts.terms["total"][subset]
    cand = np.concatenate([
        np.stack([c[:, 0] / W, c[:, 1] / D, np.minimum(wall, 2.0) / 2, (wall < 0.15).astype(float),
                  np.hypot(c[:, 0] - W / 2, c[:, 1] - D / 2) / np.hypot(W, D)], 1), rot,
        np.stack([opts.terms[t][subset] for t in TERMS], 1),
        np.stack([total - total.min(), opts.soft[subset] / 10], 1)], 1).astype(np.float32)
    return Observation(glob, nodes, edges, cand, subset)
