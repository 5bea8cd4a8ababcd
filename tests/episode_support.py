"""Shared by the repair tests: a plan's greedy episode, as the repairs find it or after the polish, and what a
repair may not worsen."""

from __future__ import annotations

from models.energy.exact import layout_energy
from models.metrics import scene_metrics
from models.placement.greedy import Episode
from models.placement.polish import polish


def finished(plan, fixed=None) -> Episode:
    """The plan placed greedily, object by object, before any repair."""
    ep = Episode(plan, fixed)
    ep.finish_greedily()
    return ep


def polished(plan, fixed=None) -> Episode:
    """`finished`, then the constraints' polish: what the passes after the polish start from."""
    ep = finished(plan, fixed)
    polish(ep)
    return ep


def judged(plan, ep: Episode):
    """The layout's scene metrics, its exact energy and how many task objects are out of the robot's reach."""
    layout = ep.layout("greedy", 0, 0.0)
    return scene_metrics(plan, layout), layout_energy(plan, layout.placements).total, len(ep.reach.unreachable(ep.placed))
