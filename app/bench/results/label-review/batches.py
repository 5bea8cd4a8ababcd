"""The readers' batches of the blind label review (decision.md) -> batches/batch_<k>.txt, batches/round2_<k>.txt.

Each round's rows are shuffled with its seed and dealt into its number of batches. Each batch also holds
`TWICE` rows of the next batch, so that those rows are read twice.
- Round 1: id_eval and valid_unseen.
- Round 2: ts and os, each source prefixed with its set.

One line a row: `source | task type | instruction | Type[roles]` (K key, A anchor, I inference). What the
readers wrote is models/data/language/label_review_eval.jsonl: one line a reading, with its round and its
reader's batch number.

    python app/bench/results/label-review/batches.py
"""

import random
from pathlib import Path

from models.datasets.language_sets import load_language_set

HERE = Path(__file__).parent
TWICE = 6
ROUNDS = {1: (("id_eval", "valid_unseen"), 2611, 8), 2: (("ts", "os"), 2612, 6)}  # sets, seed, readers
ROLE_ORDER = {"key": "K", "anchor": "A", "inference": "I"}


def line(r, prefix: str = "") -> str:
    objects = " ".join(f"{o.type}[{'/'.join(ROLE_ORDER[x] for x in ROLE_ORDER if x in o.roles)}]"
                       for o in r.label.objects)
    return f"{prefix}{r.source} | {r.task_type} | {r.instruction.replace(chr(10), ' ')} | {objects}"


def batches(round_: int) -> list[list[str]]:
    """Each reader's lines in a round."""
    sets, seed, readers = ROUNDS[round_]
    rows = [line(r, "" if round_ == 1 else f"{n}:") for n in sets for r in load_language_set(n)]
    rng = random.Random(seed)
    order = list(range(len(rows)))
    rng.shuffle(order)
    dealt = [order[k::readers] for k in range(readers)]
    out = []
    for k in range(readers):
        mine = dealt[k] + dealt[(k + 1) % readers][:TWICE]
        rng.shuffle(mine)
        out.append([rows[i] for i in mine])
    return out


if __name__ == "__main__":
    (HERE / "batches").mkdir(exist_ok=True)
    for round_, name in ((1, "batch"), (2, "round2")):
        for k, lines in enumerate(batches(round_)):
            (HERE / "batches" / f"{name}_{k}.txt").write_text("\n".join(lines) + "\n")
