"""Does the pipeline's memory level off in a long-running studio, and what is it made of? The resident set of one
process: after importing numba and loading one compiled kernel (the placers' inner loops, models.compiled; the
studio bench's run before numba came in, git da566b0, measured +50 MB with one scene open), then generating the
studio bench's instructions (rule parser, plan2place) one after another, every 10 scenes. Run from a tree's root:
PYTHONPATH=. python app/bench/results/studio-memory.py > app/bench/results/studio-memory.txt"""

import gc

import numpy as np

from app.bench.generate import pick_instructions
from app.pipeline import Pipeline
from models.language import RuleParser

SCENES = 80


def rss_mb() -> int:
    return int(open("/proc/self/status").read().split("VmRSS:")[1].split()[0]) // 1024


def main() -> None:
    instructions = pick_instructions(SCENES)
    before = rss_mb()
    import numba  # noqa: F401  (what a placer's first solve imports)
    imported = rss_mb()
    from models.energy.navigation import reachable_from
    reachable_from(np.zeros((4, 4), bool), np.eye(4, dtype=bool))  # numba's compiler and one kernel, from its cache
    kernel = rss_mb()
    pipeline = Pipeline(parser=RuleParser())
    rows = []
    for i, (text, room) in enumerate(instructions):
        pipeline.generate(text, room, seed=i)
        if i % 10 == 9:
            gc.collect()
            rows.append(f"{i + 1}: {rss_mb()} MB")
    print(f"resident set: {before} MB before the pipeline; numba imported +{imported - before} MB, its compiler and "
          f"one kernel loaded +{kernel - imported} MB; after N scenes generated in this process: " + ", ".join(rows))


if __name__ == "__main__":
    main()
