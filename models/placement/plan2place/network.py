"""The actor-critic network: MSCF (global MLP + two-layer GraphSAGE with average pooling, fused by
multi-head cross-attention and a feed-forward network), SFF (gated projection of the semantic features)
feeding the critic, and an actor that scores each candidate pose against the fused state.

The actor is a residual over the immediate energy: its logit for a candidate is the network's output minus
the candidate's per-step energy above the best one, divided by `prior_temp`. The untrained network is thus
close to the greedy placer, and what training learns is where to depart from it (look-ahead). Without the
prior (prior_temp=0) the policy starts uniform over ~48 candidates and, in 320 CPU episodes, reached a final
energy of 0.84 against greedy's 0.40 on 12 validation plans (README, Plan2Place).
"""

from __future__ import annotations

import torch
from torch import nn

from models.placement.plan2place.features import CAND_DIM, ENERGY_GAP, GLOBAL_DIM, NODE_DIM, Observation
from models.placement.plan2place.policy import NetConfig


class Plan2PlaceNet(nn.Module):
    def __init__(self, cfg: NetConfig = NetConfig()):
        super().__init__()
        from torch_geometric.nn import SAGEConv  # lazy: only the agent needs torch_geometric
        h = cfg.hidden
        self.cfg = cfg
        self.glob = nn.Sequential(nn.Linear(GLOBAL_DIM, h), nn.ReLU(), nn.Linear(h, h))
        self.sage1, self.sage2 = SAGEConv(NODE_DIM, h), SAGEConv(h, h)
        if cfg.fusion in ("cross", "self"):
            self.attn = nn.MultiheadAttention(h, cfg.heads, batch_first=True)
        else:
            self.cat = nn.Linear(2 * h, h)
        self.ffn = nn.Sequential(nn.LayerNorm(h), nn.Linear(h, h), nn.ReLU(), nn.Linear(h, h))
        if cfg.sff:
            self.gate = nn.Linear(cfg.semantic_dim, h)
            self.proj = nn.Linear(cfg.semantic_dim, h)
            self.norm = nn.LayerNorm(h)
            self.compress = nn.Linear(h, h // 2)
        self.critic = nn.Sequential(nn.Linear(h + (h // 2 if cfg.sff else 0), h), nn.ReLU(), nn.Linear(h, 1))
        self.cand = nn.Sequential(nn.Linear(CAND_DIM, h), nn.ReLU())
        self.actor = nn.Sequential(nn.Linear(2 * h, h), nn.ReLU(), nn.Linear(h, 1))

    def state(self, obs: Observation, fast: bool = False) -> torch.Tensor:
        hg = self.glob(torch.from_numpy(obs.glob))  # (h,)
        x = torch.from_numpy(obs.nodes)
        ei = torch.from_numpy(obs.edges)
        if fast:  # the same arithmetic as SAGEConv, without its message-passing machinery (inference)
            src, dst = ei[0], ei[1]
            count = x.new_zeros(len(x)).scatter_add_(0, dst, x.new_ones(len(dst))).clamp(min=1)[:, None]
            hl = torch.relu(_sage(self.sage2, torch.relu(_sage(self.sage1, x, src, dst, count)), src, dst, count))
        else:
            hl = torch.relu(self.sage2(torch.relu(self.sage1(x, ei)), ei))  # (V, h)
        pooled = hl.mean(0)
        if self.cfg.fusion == "cross":  # global as the query, local nodes (and their mean) as keys/values
            kv = torch.cat([pooled[None], hl])[None]
            fused = self.attn(hg[None, None], kv, kv, need_weights=False)[0][0, 0] + hg
        elif self.cfg.fusion == "self":
            seq = torch.stack([hg, pooled])[None]
            fused = self.attn(seq, seq, seq, need_weights=False)[0][0].mean(0) + hg
        else:
            fused = self.cat(torch.cat([hg, pooled]))
        return fused + self.ffn(fused)

    def policy(self, obs: Observation) -> torch.Tensor:
        """The logits of `forward` without the critic (which only training needs), bit for bit (tested)."""
        with torch.inference_mode():
            return self._logits(self.state(obs, fast=True), obs)

    def _logits(self, f: torch.Tensor, obs: Observation) -> torch.Tensor:
        c = self.cand(torch.from_numpy(obs.cands))
        logits = self.actor(torch.cat([f.expand(len(c), -1), c], 1)).squeeze(1)
        if self.cfg.prior_temp > 0:  # a residual policy over the immediate-energy ranking (see features)
            logits = logits - torch.from_numpy(obs.cands[:, ENERGY_GAP]) / self.cfg.prior_temp
        return logits

    def forward(self, obs: Observation, semantic: torch.Tensor | None = None) -> tuple[torch.Tensor, torch.Tensor]:
        """(logits over the K candidates, value)."""
        f = self.state(obs)
        logits = self._logits(f, obs)
        crit_in = f
        if self.cfg.sff:
            s = semantic if semantic is not None else torch.zeros(self.cfg.semantic_dim)
            fs = self.compress(self.norm(torch.sigmoid(self.gate(s)) * self.proj(s)))
            crit_in = torch.cat([f, fs])
        return logits, self.critic(crit_in).squeeze()


def _sage(conv, x: torch.Tensor, src: torch.Tensor, dst: torch.Tensor, count: torch.Tensor) -> torch.Tensor:
    """SAGEConv (mean aggregation, root weight) as torch_geometric computes it: messages x[src] summed onto
    dst by scatter_add_, divided by the in-degree clamped at 1, then lin_l(mean) + lin_r(x)."""
    msg = x.index_select(0, src)
    agg = x.new_zeros(len(x), x.shape[1]).scatter_add_(0, dst[:, None].expand_as(msg), msg) / count
    return conv.lin_l(agg) + conv.lin_r(x)
