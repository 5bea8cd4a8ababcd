"""How the placers' repairs and look-ahead order poses by energy: on a grid of `RESOLUTION` first, so that poses of
equal energy tie whatever the last bits of their float sums (which a sum's order and the CPU's maths change), and a
tie goes to the pose first in candidate order. Ordered by the raw floats, a change of one unit in the last place
of the candidates' totals changed 29 of 40 Plan2Place layouts on `seen` (README, Plan2Place; experiment log,
"Ties broken by the last bit of a float"). The step-wise placers' own picks break ties by a seeded draw instead
(`greedy.tie_broken`)."""

from __future__ import annotations

import numpy as np

RESOLUTION = 1e-9  # energies closer than this may be equal poses' sums rounded differently


def steady(energy: np.ndarray) -> np.ndarray:
    """`energy` in units of `RESOLUTION`, rounded: what `argmin`, `lexsort` and stable `argsort` order poses by."""
    return np.round(np.asarray(energy) / RESOLUTION)
