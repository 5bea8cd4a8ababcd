"""The readers' batches of the blind label review (decision.md) -> batches/batch_<k>.txt.

All id_eval and valid_unseen rows are shuffled with a fixed seed and dealt into `READERS` batches. Each batch
also holds `TWICE` rows of the next batch, so that those rows are read twice. One line a row:
`source | task type | instruction | Type[roles]` (K key, A anchor, I inference). What the readers wrote is
models/data/language/label_review_eval.jsonl, one line a reading with its reader's batch number.

    python app/bench/results/label-review/batches.py
"""

import random
from pathlib import Path

from models.datasets.language_sets import load_language_set

HERE = Path(__file__).parent
SEED, READERS, TWICE = 2611, 8, 6
ROLE_ORDER = {"key": "K", "anchor": "A", "inference": "I"}


def line(r) -> str:
    objects = " ".join(f"{o.type}[{'/'.join(ROLE_ORDER[x] for x in ROLE_ORDER if x in o.roles)}]"
                       for o in r.label.objects)
    return f"{r.source} | {r.task_type} | {r.instruction.replace(chr(10), ' ')} | {objects}"


def batches() -> list[list]:
    rows = [r for n in ("id_eval", "valid_unseen") for r in load_language_set(n)]
    rng = random.Random(SEED)
    order = list(range(len(rows)))
    rng.shuffle(order)
    dealt = [order[k::READERS] for k in range(READERS)]
    out = []
    for k in range(READERS):
        mine = dealt[k] + dealt[(k + 1) % READERS][:TWICE]
        rng.shuffle(mine)
        out.append([rows[i] for i in mine])
    return out


if __name__ == "__main__":
    (HERE / "batches").mkdir(exist_ok=True)
    for k, rows in enumerate(batches()):
        (HERE / "batches" / f"batch_{k}.txt").write_text("\n".join(line(r) for r in rows) + "\n")
