"""Is this machine's speed steady? The same Plan2Place solve (one `dense` bench plan, seed 0) again and again, each
after a fixed pure-Python loop, both timed in CPU time: if the machine's speed changes, both change together. Run
from a tree's root:
PYTHONPATH=. python app/bench/results/plan2place/speed/machine-states.py 80   (rounds)"""
import statistics
import sys
import time

from app.bench.placement import pick_records
from models.placement.base import get_solver


def spin() -> float:
    """ms of CPU time for a fixed pure-Python loop."""
    t, x = time.process_time(), 0
    for i in range(300_000):
        x += i * i
    return 1000 * (time.process_time() - t)


rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 80
plan = [r.plan for r in pick_records("dense", 20)][3]
solver = get_solver("plan2place")
solver.solve(plan, seed=0)  # the compiled kernels and the caches
rows = []
for _ in range(rounds):
    loop = spin()
    t = time.process_time()
    solver.solve(plan, seed=0)
    rows.append((loop, 1000 * (time.process_time() - t) / len(plan.objects)))
print(f"{plan.id}, seed 0, {len(plan.objects)} objects, {rounds} rounds; CPU ms: (loop, Plan2Place per object)")
print(" ".join(f"({a:.1f}, {b:.1f})" for a, b in rows))
cut = statistics.median(a for a, _ in rows)
fast = [b for a, b in rows if a < 0.8 * cut] or [b for a, b in rows if a <= cut]
slow = [b for a, b in rows if a >= 0.8 * cut]
loops = sorted(a for a, _ in rows)
print(f"loop: min {loops[0]:.1f}, p25 {loops[len(loops) // 4]:.1f}, median {cut:.1f}, p75 "
      f"{loops[3 * len(loops) // 4]:.1f}, max {loops[-1]:.1f} ms")
print(f"Plan2Place per object after a loop under 0.8 x the median loop: median {statistics.median(fast):.1f} ms "
      f"({len(fast)} rounds); the others: median {statistics.median(slow):.1f} ms ({len(slow)} rounds)")
r = statistics.correlation([a for a, _ in rows], [b for _, b in rows])
print(f"correlation of the two over the rounds: {r:.2f}")
