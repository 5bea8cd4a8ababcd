"""The exact energy of a layout, on polygons (shapely): what judges a layout and what the tests trust."""

from __future__ import annotations

import math
from collections.abc import Collection
from dataclasses import dataclass

import numpy as np
from shapely.geometry import box as shapely_box

from models.constraints.evaluate import Poses, placement, relation
from models.energy import navigation as nav
from models.energy.prior import WALL_TOUCH, relation_prior
from models.energy.weights import AFF_BLOCKED, AFF_OUTSIDE, EPS, PRIOR_LAMBDA, WEIGHTS
from models.geometry import Footprint, gap, intersection_area, wall_clearance
from models.placement.problem import PlacementProblem
from models.values import ConstraintPlan, Placement

OVERLAP_TOL = 1e-4


@dataclass(frozen=True)
class EnergyTerms:
    rel: float
    collision: float
    oob: float
    nav: float
    aff: float
    missing: float = 0.0

    @property
    def total(self) -> float:
        return sum(WEIGHTS[k] * getattr(self, k) for k in WEIGHTS)

    def as_dict(self) -> dict[str, float]:
        return {**{k: getattr(self, k) for k in WEIGHTS}, "total": self.total}


def layout_energy(plan: ConstraintPlan, placements: list[Placement], problem: PlacementProblem | None = None,
                  pending: Collection[str] = ()) -> EnergyTerms:
    """Energy of a (possibly partial) layout. Every plan object that is not placed is charged by E_missing
    and, if it is a task object, counts as unreachable in E_nav; except the ids in `pending`, the objects
    a placer has still to place (a per-step RL reward passes them; a finished layout passes none)."""
    problem = problem or PlacementProblem.from_plan(plan)
    room = plan.room
    fps = {p.id: Footprint(p.x, p.z, p.size.x, p.size.z, p.rotation) for p in placements}
    polys = {k: f.polygon() for k, f in fps.items()}
    types = {o.id: o.type for o in plan.objects}
    ids = list(fps)

    # relational
    prior = relation_prior()
    total, count = 0.0, 0
    for oid in ids:
        oc = problem.constraints.objects[oid]
        f = fps[oid]
        pose = Poses.one(f.x, f.z, f.rotation, f.width, f.depth)
        clearance = wall_clearance(f, room.width, room.depth)
        e, _ = placement(oc.placement, pose, room.width, room.depth, clearance=np.array([clearance]))
        touching = clearance <= WALL_TOUCH
        total += float(e[0]) * (1 + PRIOR_LAMBDA * float(prior.wall_energy(room.type, types[oid], touching)))
        count += 1
        for c in oc.relations:
            if c.target not in fps:
                continue
            t = fps[c.target]
            g = gap(f, t)
            e, _ = relation(c.name, pose, Poses.one(t.x, t.z, t.rotation, t.width, t.depth), gap=np.array([g]))
            pe = prior.pair_energy(room.type, types[oid], types[c.target], g, f.rotation - t.rotation)
            total += float(e[0]) * (1 + PRIOR_LAMBDA * float(pe))
            count += 1
    rel = math.log1p(total / max(count, 1))

    # collision and out-of-bounds
    overlaps = sum(intersection_area(polys[a], polys[b]) ** 2 for i, a in enumerate(ids) for b in ids[i + 1:])
    collision = math.log1p(overlaps)
    room_poly = shapely_box(0, 0, room.width, room.depth)
    oob = math.log1p(sum((1 - intersection_area(poly, room_poly) / (poly.area + EPS)) ** 2 for poly in polys.values()))

    # affordance: the clearance region in front of functional objects
    aff_sum, functional = 0.0, 0
    for oid in ids:
        depth = problem.clearance.get(oid, 0.0)
        if depth <= 0:
            continue
        functional += 1
        zone = fps[oid].front_zone(depth).polygon()
        aff_sum += AFF_OUTSIDE * (not zone.difference(room_poly).area <= OVERLAP_TOL)
        aff_sum += AFF_BLOCKED * sum(1 for other in ids if other != oid and not problem.constraints.tied(oid, other)
                                     and intersection_area(zone, polys[other]) > OVERLAP_TOL)
    aff = aff_sum / max(functional, 1)

    # navigation: can the robot reach the front of every task object from the door? (unplaced: no)
    due = [o.id for o in plan.objects if o.id in fps or o.id not in pending]
    targets = [o.id for o in plan.objects if o.is_task and o.id in due]
    if targets:
        grid = nav.Grid(room.width, room.depth)
        reachable = nav.reachable_space(grid, nav.blocked_by_polygons(grid, list(polys.values())), room)
        rho = sum(t in fps and nav.can_reach(grid, reachable, fps[t]) for t in targets) / len(targets)
        nav_e = (1 - rho) ** 2
    else:
        nav_e = 0.0
    missing = sum(oid not in fps for oid in due) / len(plan.objects) if plan.objects else 0.0
    return EnergyTerms(rel=rel, collision=collision, oob=oob, nav=nav_e, aff=aff, missing=missing)


__all__ = ["EnergyTerms", "layout_energy"]
