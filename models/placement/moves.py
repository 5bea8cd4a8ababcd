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
from models.placement.ties import steady

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
    cands = ep.scorer.bodies(obj)[0]
    legal = legal_poses(ep, obj, placed, cands, ep.scorer.swept(obj), relax)
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
                  tries: int = TRIES, strips: bool = False) -> list[tuple[int, list[str]]]:
    """Poses of `cands` that `obj` could take if at most `MAX_BLOCKERS` of `placed` (none fixed) were moved
    away: (pose index, the ids in the way, largest first), highest `rank` first (default: all equal), then
    fewest in the way, then lowest energy (the overlap with them not counted; `energy`: makes the set-up for
    `placed`, if there is a cheaper way), at most `tries`. With `strips`, an object is also in the way where
    the pose and it stand in each other's front clearance (the strict hard filter's rule), and the pose's own
    clearance must lie inside the room."""
    way = np.zeros((len(cands), len(placed)), bool)  # pose i overlaps placed object j
    for j, (idx, area) in enumerate(swept.overlaps(np.array([p.body for p in placed]).reshape(-1, 4))):
        way[idx[area > OVERLAP_TOL], j] = True
    if strips:
        _mark_strips(ep, obj, cands, swept, placed, way)
    fixed = np.array([p.id in ep.problem.fixed for p in placed], bool)
    count = way.sum(axis=1)
    free = hard_filter(ep.scorer, obj, [], cands, swept, strips)[0]  # inside, doorways clear
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
    order = np.lexsort((steady(cost), count[options], -rank[options]))[:tries]
    area = {p.id: p.width * p.depth for p in placed}
    return [(int(options[k]), sorted((placed[j].id for j in np.flatnonzero(way[options[k]])), key=lambda i: -area[i]))
            for k in order]


def _mark_strips(ep: Episode, obj, cands: np.ndarray, swept: SweptBoxes, placed: list[PlacedObject],
                 way: np.ndarray) -> None:
    """Mark in `way` (poses x placed) the placed objects standing in a pose's front clearance, or whose own
    front clearance the pose stands in; pairs tied by a front relation (a chair at its desk) excepted."""
    tied, depth = ep.problem.constraints.tied, ep.problem.clearance.get(obj.id, 0.0)
    free = [j for j, p in enumerate(placed) if not tied(obj.id, p.id)]
    theirs = [j for j in free if placed[j].front is not None]
    pairs = [(swept, theirs, [placed[j].front for j in theirs])]  # the pose in their clearance
    if depth > 0:  # they in the pose's
        pairs.append((ep.scorer.strips(obj, cands, swept)[1], free, [placed[j].body for j in free]))
    for boxes_, js, others in pairs:
        for j, (idx, area) in zip(js, boxes_.overlaps(np.array(others).reshape(-1, 4))):
            way[idx[area > OVERLAP_TOL], j] = True
