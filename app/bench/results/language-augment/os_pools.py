"""The OS sets split by the pool of the new target (rare_target_pools: training pool, held out), for the
previous and the augmented adapter, from the cached readings only (no decoding). Writes os_pools.md.

    PYTHONPATH=. python app/bench/results/language-augment/os_pools.py
"""

from __future__ import annotations

import sys
from pathlib import Path

from app.bench.language import CONFIRMATION, confirmation_sets, lora_readings, read_all, readings_cache, score_parsers

HERE = Path(__file__).parent


class _Cached:
    """Stands in for the model: every reading must already be cached."""

    def load(self):
        raise RuntimeError("a reading is missing from the cache")


def main() -> int:
    from models.datasets.language_sets import load_language_set, rare_target_pools
    from models.language import RuleParser
    from models.language.combined import CombinedParser

    train_pool, held_out = rare_target_pools()
    sets = {"os": list(load_language_set("os")), "confirm os": list(confirmation_sets()[CONFIRMATION[2]])}
    split = {f"{name}, {label}": [r for r in rows if r.label.target in pool]
             for name, rows in sets.items() for label, pool in (("held-out types", held_out),
                                                                ("training-pool types", train_pool))}
    rows = [r for s in sets.values() for r in s]
    rules = RuleParser()
    scored: dict[str, dict] = {name: {} for name in split}
    for label, cache in (("previous", HERE.parent / "language-lora-readings-368015fd8e.jsonl"),
                         ("augmented", readings_cache(HERE / "adapter"))):
        readings = lora_readings(rows, _Cached(), cache, progress=False)
        graphs, seconds = read_all(rows, readings, rules, {"combined": CombinedParser(rules=rules)})
        for name, set_rows in split.items():
            for parser, r in score_parsers(set_rows, graphs, seconds).items():
                scored[name][parser if parser == "rules" else f"{parser} ({label})"] = r
    columns = list(scored[next(iter(split))])
    lines = ["OS sets split by the new target's pool (rare_target_pools); object F1 / iRecall / GED, room type given",
             "", "| set | n | " + " | ".join(columns) + " |", "| --- | ---: |" + " --- |" * len(columns)]
    lines += [f"| {name} | {r['rules']['n']} | " + " | ".join(
        f"{100 * r[c]['object_f1']:.2f} / {100 * r[c]['irecall']:.2f} / {r[c]['ged']:.2f}" for c in columns) + " |"
        for name, r in scored.items()]
    print("\n".join(lines))
    (HERE / "os_pools.md").write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
