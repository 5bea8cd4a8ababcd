"""One BLAS thread while a placer runs: the step-wise ones (greedy, look-ahead, Plan2Place) and DFS, which compute
the same kind of energies (MILP and Z3 spend their time in HiGHS and Z3, which have their own threads).

Their matrices are small: the policy's are tens of rows by 128 columns, the energy's a few hundred candidates by a
few numbers. numpy's OpenBLAS still splits such products across its threads, whose waits spin. On an idle machine
that gains nothing measurable; with anything else wanting the same cores (a second bench worker, the studio's
server, another solve) the spinning threads made Plan2Place twice as slow on this 2-core machine
(`app/bench/results/plan2place/speed/blas-threads.txt`). OpenBLAS keeps one thread count per process, so the limit
holds for the whole process while a solve runs, and numpy's own setting is put back after it.
"""

from __future__ import annotations

from contextlib import AbstractContextManager
from functools import cache


@cache
def _controller():
    """The BLAS libraries loaded in this process, found once (~3 ms); limiting through it takes ~30 us."""
    from threadpoolctl import ThreadpoolController
    return ThreadpoolController()


def one_blas_thread() -> AbstractContextManager:
    """Within it, BLAS calls run on the calling thread alone."""
    return _controller().limit(limits=1, user_api="blas")
