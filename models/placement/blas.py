"""One BLAS thread while a placer runs: the step-wise ones (greedy, look-ahead, Plan2Place) and DFS, which compute
the same kind of energies (MILP and Z3 spend their time in HiGHS and Z3, which have their own threads).

Their matrices are small: the policy's are tens of rows by 128 columns, the energy's a few hundred candidates by a
few numbers. numpy's OpenBLAS still splits such products across its threads, whose waits spin. On an idle machine
that gains nothing measurable; with anything else wanting the same cores (a second bench worker, the studio's
server, another solve) the spinning threads made Plan2Place three to four times slower on this 2-core machine
(`app/bench/results/plan2place/speed/blas-threads.txt`). OpenBLAS keeps one thread count per process, so the limit
holds for the whole process while any solve runs (the studio solves in worker threads, maybe two at once), and
numpy's own setting is put back when the last one ends.
"""

from __future__ import annotations

import threading
from functools import cache


@cache
def _controller():
    """The BLAS libraries loaded in this process, found once (~3 ms); limiting through it takes ~30 us."""
    from threadpoolctl import ThreadpoolController
    return ThreadpoolController()


def _any_thread_may_set() -> None:
    """threadpoolctl lets only one Python thread at a time change OpenBLAS's process-wide thread count (the first
    that did, while it lives) and silently ignores the others; the studio solves in worker threads. The solves under
    way are counted here, under a lock, so the thread that changes the count may take that right."""
    from threadpoolctl import OpenBLASController
    OpenBLASController.clear_controlling_thread(force=True)


class _OneThread:
    """The limit shared by every solve under way, nested or in other threads: the first in sets it, the last out
    puts numpy's setting back."""

    def __init__(self):
        self._lock, self._inside, self._limiter = threading.Lock(), 0, None

    def __enter__(self) -> None:
        with self._lock:
            if not self._inside:
                _any_thread_may_set()
                self._limiter = _controller().limit(limits=1, user_api="blas")
            self._inside += 1

    def __exit__(self, *exc) -> None:
        with self._lock:
            self._inside -= 1
            if not self._inside:
                _any_thread_may_set()
                self._limiter.restore_original_limits()
                _any_thread_may_set()  # and after it, for whatever else in the process limits threads


_ONE_THREAD = _OneThread()


def one_blas_thread() -> _OneThread:
    """Within it, BLAS calls run on the calling thread alone."""
    return _ONE_THREAD
