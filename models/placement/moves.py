"""Moving objects of a finished episode (shared by the repairs and the polish): the legal poses of an object
among the others and their energy, the poses it could take if a few objects made way, and the placement step
each move shows the observer (which task objects the robot reaches: models.placement.reach)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from models.energy.vectorised import CandidateEnergy
from models.energy.weights import WEIGHTS
from models.geometry import SweptBoxes
from models.placement.base import PlacementStep
from models.placement.candidates import OVERLAP_TOL, PlacedObject
from models.placement.greedy import Episode, hard_filter

MAX_BLOCKERS, TRIES = 3, 5  # displacements


def legal_poses(ep: Episode, obj, placed: list[PlacedObject], cands: np.ndarray, swept: SweptBoxes,
                relax: bool = True) -> np.ndarray:
    """Indices of the legal poses among `cands`; with `relax`, the front-clearance rules relaxed if none
    is legal with them (as `Episode.options` does)."""
    ok, _ = hard_filter(ep.scorer, obj, placed, cands, swept, True)
    if relax and not ok.any():
        ok, _ = hard_filter(ep.scorer, obj, placed, cands, swept, False)
    return np.flatnonzero(ok)


def scored(ep: Episode, obj, placed: list[PlacedObject], pending=(), relax: bool = True):
    """(every candidate pose of `obj`, the indices of the legal ones, their energy terms with `placed` where
    they are and `pending` still to come); no terms when none is legal."""
    cands, body = ep.scorer.bodies(obj)
    legal = legal_poses(ep, obj, placed, cands, SweptBoxes(body), relax)
    if not len(legal):
        return cands, legal, {}
    return cands, legal, CandidateEnergy(ep.problem, placed, pending=pending).score(obj, cands[legal])


def move_step(obj_id: str, pose: PlacedObject, cands: np.ndarray, legal: np.ndarray, k: int,
              terms: dict, why: str) -> PlacementStep:
    """The step a move shows: the chosen pose `legal[k]` as the only choice among the legal ones, and `why`."""
    scores = np.full(len(cands), -np.inf)
    scores[legal], scores[legal[k]] = 0.0, 1.0
    return PlacementStep(obj_id, pose.x, pose.z, pose.rotation, cands, scores,
                         {t: float(v[k]) for t, v in terms.items()}, why)


def displacements(ep: Episode, obj, cands: np.ndarray, swept: SweptBoxes, placed: list[PlacedObject],
                  rank: np.ndarray | None = None, energy: Callable[[], CandidateEnergy] | None = None,
                  tries: int = TRIES) -> list[tuple[int, list[str]]]:
    """Poses of `cands` that `obj` could take if at most `MAX_BLOCKERS` of `placed` (none fixed) were moved
    away: (pose index, the ids in the way, largest first), highest `rank` first (default: all equal), then
    fewest in the way, then lowest energy (the overlap with them not counted; `energy`: makes the set-up for
    `placed`, if there is a cheaper way), at most `tries`."""
    way = np.zeros((len(cands), len(placed)), bool)  # pose i overlaps placed object j
    for j, p in enumerate(placed):
        for idx, area in swept.overlaps(p.body[None]):
            way[idx[area > OVERLAP_TOL], j] = True
    fixed = np.array([p.id in ep.problem.fixed for p in placed], bool)
    count = way.sum(axis=1)
    free = hard_filter(ep.scorer, obj, [], cands, swept, False)[0]  # inside, doorways clear
    options = np.flatnonzero(free & (count > 0) & (count <= MAX_BLOCKERS) & ~way[:, fixed].any(axis=1))
    if not len(options):
        return []
    rank = np.zeros(len(cands)) if rank is None else rank
    first = np.lexsort((count[options], -rank[options]))  # stable: pose order breaks ties
    # the energy is needed only to order the options tied with the `tries`-th best on (rank, count)
    last = first[min(tries, len(first)) - 1]
    key = (-rank[options], count[options])
    keep = np.flatnonzero((key[0] < key[0][last]) | ((key[0] == key[0][last]) & (key[1] <= key[1][last])))
    options = options[keep]
    setup = energy() if energy is not None else CandidateEnergy(ep.problem, placed, pending=())
    terms = setup.score(obj, cands[options])
    cost = terms["total"] - WEIGHTS["collision"] * terms["collision"]
    order = np.lexsort((cost, count[options], -rank[options]))[:tries]
    area = {p.id: p.width * p.depth for p in placed}
    return [(int(options[k]), sorted((placed[j].id for j in np.flatnonzero(way[options[k]])), key=lambda i: -area[i]))
            for k in order]
