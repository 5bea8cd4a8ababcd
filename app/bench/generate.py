"""Wall time of the whole pipeline (`generate`) on ALFRED valid_unseen instructions, in process.

Prints p50 / p90 of generate (every stage plus the house JSON and GLB, in memory) over N instructions after one warm-up run, the share spent placing,
and the DFS placer's time per object; the ratio of generate to a bare parse is the in-process
baseline that makes the figures comparable across machines.
"""

from __future__ import annotations

import statistics
import time

from app.pipeline import Pipeline
from models.language import RuleParser
from models.exports.glb import to_glb
from models.exports.procthor_house import to_house
from models.language.alfred import load_annotations


def pick_instructions(n: int) -> list[tuple[str, str]]:
    """n instructions spread evenly over valid_unseen (all four task types and room types)."""
    rows = load_annotations("valid_unseen")
    step = max(len(rows) // n, 1)
    return [(r.instruction, r.room_type) for r in rows[::step][:n]]


def quantile(values: list[float], q: float) -> float:
    return statistics.quantiles(values, n=100, method="inclusive")[int(q * 100) - 1] if len(values) > 1 else values[0]


def main(args) -> int:
    if getattr(args, "room_type", None):
        from app.bench.generate_apartment import main as apartment
        return apartment(args)
    pipeline = Pipeline(parser=RuleParser(), solver="dfs")  # the rules, as the figures in the README
    items = pick_instructions(args.n)
    pipeline.generate(*items[0], seed=0)  # warm-up: catalogue load, imports
    totals, place_times, per_object, parse_times, skipped = [], [], [], [], 0
    for i, (instruction, room) in enumerate(items):
        t0 = time.perf_counter()
        try:
            pipeline.parse(instruction, room)
        except ValueError:
            skipped += 1
            continue
        parse_times.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        gen = pipeline.generate(instruction, room, seed=i)
        to_house(gen.scene), to_glb(gen.scene)
        totals.append(time.perf_counter() - t0)
        place_times.append(gen.layout.timing.total_s)
        per_object.append(gen.layout.timing.per_object_s)
    print(f"generate on {len(totals)} ALFRED valid_unseen instructions ({skipped} unparseable skipped), dfs placer")
    print(f"  generate wall time      p50 {1000 * quantile(totals, .5):8.1f} ms   p90 {1000 * quantile(totals, .9):8.1f} ms")
    print(f"  placing (dfs) share     {100 * sum(place_times) / sum(totals):5.1f} % of generate")
    print(f"  dfs time per object     p50 {1000 * quantile(per_object, .5):8.2f} ms   p90 "
          f"{1000 * quantile(per_object, .9):8.2f} ms")
    print(f"  baseline: parse alone   p50 {1000 * quantile(parse_times, .5):8.3f} ms  -> generate / parse = "
          f"{quantile(totals, .5) / quantile(parse_times, .5):.0f}x")
    return 0
