"""What the studio's server does for a designer's move (a drag's end, a typed pose or a turn), without the browser:
the pipeline's `move` and the read-outs that follow it (the checks with their metrics, the exact energy, the habits
of the iTHOR rooms), as `PickingPanel.move_to` and `StudioSession.refresh_checks` run them. The robot's occupancy
grid is asked about three times per move (the checks, Key_NAV and NAV), each time testing every cell centre against
the furniture; the centres are now made once per room (models.energy.navigation._cell_centres). Alternates, per move,
that with the centres made afresh each time (the function the cache wraps), on N rooms of the ALFRED instructions,
5 moves each.
Run from a tree's root: PYTHONPATH=. python app/bench/results/studio-move-checks.py > app/bench/results/studio-move-checks.txt
"""

import statistics
import time

from app.bench.generate import pick_instructions
from app.pipeline import Pipeline
from models.checks import run_checks
from models.energy import navigation
from models.energy.exact import layout_energy
from models.language import RuleParser
from models.metrics.realism import checks as habit_checks

N = 20
MOVES = 5
STEP = 0.1  # m, each move along x


def read_outs(pipeline: Pipeline, gen, oid: str, k: int) -> float:
    """Seconds for one move of `oid` and its read-outs."""
    p = gen.layout.placement(oid)
    t0 = time.perf_counter()
    moved = pipeline.move(gen, oid, p.x + STEP * (1 if k % 2 else -1), p.z, p.rotation)
    run_checks(moved.plan, moved.layout, moved.scene)
    layout_energy(moved.plan, moved.layout.placements)
    habit_checks(moved.plan, moved.layout)
    return time.perf_counter() - t0


def main() -> None:
    pipeline = Pipeline(parser=RuleParser())
    kept, afresh = navigation._cell_centres, navigation._cell_centres.__wrapped__
    times = {"centres kept per room": [], "centres made afresh (before)": []}
    for i, (text, room) in enumerate(pick_instructions(N)):
        gen = pipeline.generate(text, room, seed=i)
        oid = gen.layout.placements[0].id
        for k in range(2 * MOVES):
            name = list(times)[k % 2]
            navigation._cell_centres = kept if k % 2 == 0 else afresh
            times[name].append(read_outs(pipeline, gen, oid, k))
    navigation._cell_centres = kept
    print(f"a designer's move and its read-outs, server side, {N} rooms x {MOVES} moves per variant, alternating")
    for name, runs in times.items():
        print(f"  {name:30s} p50 {1000 * statistics.median(runs):6.1f} ms   mean {1000 * statistics.mean(runs):6.1f} ms")
    new, old = (statistics.median(r) for r in times.values())
    print(f"  kept / afresh (p50)            {new / old:.2f}")


if __name__ == "__main__":
    main()
