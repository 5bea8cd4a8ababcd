"""Does the pipeline's memory level off in a long-running studio? The resident set of one process generating the
studio bench's instructions (rule parser, plan2place) one after another, every 10 scenes. Run from a tree's root:
PYTHONPATH=. python app/bench/results/studio-memory.py > app/bench/results/studio-memory.txt"""

import gc

from app.bench.generate import pick_instructions
from app.pipeline import Pipeline
from models.language import RuleParser

SCENES = 80


def rss_mb() -> int:
    return int(open("/proc/self/status").read().split("VmRSS:")[1].split()[0]) // 1024


def main() -> None:
    before = rss_mb()
    pipeline = Pipeline(parser=RuleParser())
    rows = []
    for i, (text, room) in enumerate(pick_instructions(SCENES)):
        pipeline.generate(text, room, seed=i)
        if i % 10 == 9:
            gc.collect()
            rows.append(f"{i + 1}: {rss_mb()} MB")
    print(f"resident set: {before} MB before the pipeline; after N scenes generated in this process: " + ", ".join(rows))


if __name__ == "__main__":
    main()
