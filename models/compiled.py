"""Inner loops compiled by numba: each is written as plain Python over numpy arrays and compiled at its first
call, then cached on disk (numba's cache), so that numba is imported only when a placer first needs it and the
CLI and the studio start without it."""

from __future__ import annotations

from collections.abc import Callable
from functools import wraps


def compiled(fn: Callable) -> Callable:
    """`fn` compiled by `numba.njit(cache=True)` at its first call; where numba finds no writable cache directory
    (a read-only install and no writable home), compiled for this process only."""
    kernel: list[Callable] = []

    @wraps(fn)
    def call(*args):
        if not kernel:
            from numba import njit
            try:
                kernel.append(njit(cache=True)(fn))
            except RuntimeError:  # numba: "cannot cache function ...: no locator available"
                kernel.append(njit(fn))
        return kernel[0](*args)

    return call
