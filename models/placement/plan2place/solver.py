"""Plan2Place behind the Solver interface: the trained policy picks, object by object, the most probable
of the candidate poses; the studio's heat-map is the policy's probability of every candidate."""

from __future__ import annotations

import time
from functools import cache
from importlib import resources

import numpy as np
import torch

from models.placement.base import Fixed, StepObserver
from models.placement.plan2place.agent import rollout
from models.placement.plan2place.network import NetConfig, Plan2PlaceNet
from models.values import ConstraintPlan, Layout

WEIGHTS = "weights/plan2place/plan2place.pt"


@cache
def shipped_network() -> Plan2PlaceNet:
    with resources.files("models").joinpath(WEIGHTS).open("rb") as fh:
        state = torch.load(fh, weights_only=False)
    return load_network(state)


def load_network(state: dict) -> Plan2PlaceNet:
    net = Plan2PlaceNet(NetConfig(**state["config"]["net"]))
    net.load_state_dict({k: v.float() for k, v in state["net"].items()})
    net.use_global = state["config"].get("use_global", True)
    return net.eval()


def untrained_network(seed: int = 0) -> Plan2PlaceNet:
    """The same network with its initial weights: the baseline that shows what training adds."""
    torch.manual_seed(seed)
    return Plan2PlaceNet(NetConfig()).eval()


class Plan2PlaceSolver:
    name = "plan2place"

    def __init__(self, network: Plan2PlaceNet | None = None, name: str | None = None):
        self._network = network
        if name:
            self.name = name

    def solve(self, plan: ConstraintPlan, seed: int = 0, time_budget_s: float | None = None,
              observer: StepObserver | None = None, fixed: Fixed | None = None) -> Layout:
        start = time.perf_counter()
        torch.set_num_threads(1)
        net = self._network or shipped_network()
        ep, _ = rollout(net, plan, np.random.default_rng(seed), sample=False,
                        use_global=getattr(net, "use_global", True), fixed=fixed, observer=observer)
        return ep.layout(self.name, seed, time.perf_counter() - start)
