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


def observe(ep: Episode, opts: Options, subset: np.ndarray, use_global: bool = True) -> Observation:
    plan, room = ep.problem.plan, ep.problem.plan.room
    W, D, area = room.width, room.depth, room.width * room.depth
    cons = ep.problem.constraints.objects
    obj = opts.obj
    n_rel = sum(len(c.relations) for c in cons.values())
    occupied = sum(p.width * p.depth for p in ep.placed)
    glob = np.array([len(cons[obj.id].relations) / 4, n_rel / max(len(plan.objects), 1) / 4,
                     obj.size.x * obj.size.z / area, (len(ep.order) - ep.i) / max(len(ep.order), 1),
                     occupied / area], np.float32)
    if not use_global:
        glob = np.zeros_like(glob)

    objs = ep.order
    index = {o.id: k for k, o in enumerate(objs)}
    pose = {p.id: p for p in ep.placed}
    nodes = np.zeros((len(objs), NODE_DIM), np.float32)
    for k, o in enumerate(objs):
        p = pose.get(o.id)
        r = np.radians(p.rotation) if p else 0.0
        nodes[k, :10] = [o.size.x / W, o.size.z / D, p.x / W if p else 0, p.z / D if p else 0,
                         np.sin(r) if p else 0, np.cos(r) if p else 0, p is not None, o.id == obj.id, o.is_task,
                         ep.problem.clearance.get(o.id, 0.0)]
        nodes[k, 10:10 + EMBED_DIM] = embed(o.type)
    pairs = {(index[a], index[c.target]) for a, oc in cons.items() if a in index
             for c in oc.relations if c.target in index}
    pairs |= {(index[p.id], index[obj.id]) for p in ep.placed if p.id in index}
    pairs = sorted(pairs | {(b, a) for a, b in pairs})
    edges = np.array(pairs, np.int64).T.reshape(2, -1)
    if edges.shape[1]:
        feat = np.zeros((edges.shape[1], EDGE_DIM), np.float32)
        for e, (a, b) in enumerate(edges.T):
            pa, pb = pose.get(objs[a].id), pose.get(objs[b].id)
            constrained = any(c.target == objs[b].id for c in cons[objs[a].id].relations)
            if pa and pb:
                dx, dz = pb.x - pa.x, pb.z - pa.z
                dist = np.hypot(dx, dz)
                feat[e] = [dist / np.hypot(W, D), dx / (dist + 1e-6), dz / (dist + 1e-6),
                           abs(np.cos(np.radians(pa.rotation - pb.rotation))), constrained]
            else:
                feat[e, 4] = constrained
        sums = np.zeros((len(objs), EDGE_DIM), np.float32)
        np.add.at(sums, edges[1], feat)
        counts = np.bincount(edges[1], minlength=len(objs))[:, None]
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
