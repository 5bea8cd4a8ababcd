"""Wall time of the whole pipeline (`generate`) on ALFRED valid_unseen instructions, in process.

Prints, for each placer (`--solvers`; default DFS, the old default, and the default solver), p50 / p90 of
generate (every stage plus the house JSON and GLB, in memory) over N instructions after one warm-up run, the
share spent placing and the placer's time per object; the ratio of generate to a bare parse is the in-process
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
from models.metrics import scene_metrics
from models.placement import DEFAULT_SOLVER


def pick_instructions(n: int) -> list[tuple[str, str]]:
    """n instructions spread evenly over valid_unseen (all four task types and room types)."""
    rows = load_annotations("valid_unseen")
    step = max(len(rows) // n, 1)
    return [(r.instruction, r.room_type) for r in rows[::step][:n]]


def quantile(values: list[float], q: float) -> float:
    return statistics.quantiles(values, n=100, method="inclusive")[int(q * 100) - 1] if len(values) > 1 else values[0]


def placers(args) -> list[str]:
    """The solvers a generate bench compares: `--solvers`, else DFS (the default before) and the default."""
    names = getattr(args, "solvers", None) or f"dfs,{DEFAULT_SOLVER}"
    return list(dict.fromkeys(s.strip() for s in names.split(",") if s.strip()))


def main(args) -> int:
    if getattr(args, "room_type", None):
        from app.bench.generate_apartment import main as apartment
        return apartment(args)
    for solver in placers(args):
        run(Pipeline(parser=RuleParser(), solver=solver), args.n)  # the rules, as the figures in the README
    return 0


def run(pipeline: Pipeline, n: int) -> None:
    items = pick_instructions(n)
    pipeline.generate(*items[0], seed=0)  # warm-up: catalogue load, imports
    totals, place_times, per_object, parse_times, key_nav, skipped, unplaced, objects = [], [], [], [], [], 0, 0, 0
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
        key_nav += [m.key_nav] if (m := scene_metrics(gen.plan, gen.layout)).key_nav is not None else []
        unplaced, objects = unplaced + len(gen.layout.unplaced), objects + len(gen.plan.objects)
    name = pipeline.solver
    print(f"generate on {len(totals)} ALFRED valid_unseen instructions ({skipped} unparseable skipped), {name} placer")
    print(f"  generate wall time      p50 {1000 * quantile(totals, .5):8.1f} ms   p90 {1000 * quantile(totals, .9):8.1f} ms")
    print(f"  placing share           {100 * sum(place_times) / sum(totals):5.1f} % of generate")
    print(f"  time per object         p50 {1000 * quantile(per_object, .5):8.2f} ms   p90 "
          f"{1000 * quantile(per_object, .9):8.2f} ms")
    print(f"  Key_NAV from doorway    {100 * statistics.mean(key_nav):5.1f} (mean over {len(key_nav)} scenes; "
          f"{sum(k == 0 for k in key_nav)} at 0); unplaced objects {unplaced} of {objects}")
    print(f"  baseline: parse alone   p50 {1000 * quantile(parse_times, .5):8.3f} ms  -> generate / parse = "
          f"{quantile(totals, .5) / quantile(parse_times, .5):.0f}x")
