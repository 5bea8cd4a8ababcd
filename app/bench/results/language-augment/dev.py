"""Development figures of the augmented language adapter (the rule in decision.md, written first).

    PYTHONPATH=. python app/bench/results/language-augment/dev.py --augmented runs/language-augment/adapter

The dev set: 400 policy rows (`unseen_train_rows(POLICY_ROWS)[::2][:400]`), their TS and OS versions
with seed 13 (used for this decision only). Each adapter's readings go to its own cache
(`readings_cache`); `--decode-only` fills the caches and prints no figure. Writes dev.md next to this file.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from app.bench.language import (POLICY_ROWS, lora_readings, read_all, readings_cache, report, score_parsers,
                                set_table, unseen_train_rows)

HERE = Path(__file__).parent
DEV_ROWS = 400
DEV_SEED = 13
SETS = ("dev id", "dev ts", "dev os")
METRICS = ("object_f1", "irecall")


def dev_sets() -> dict[str, list]:
    """The three decision sets, then `dev os` split by the pool of the new target (training / held out)."""
    from models.datasets.language_sets import object_shift, rare_target_pools, text_shift
    rows = unseen_train_rows(POLICY_ROWS)[::2][:DEV_ROWS]
    shifted = object_shift(rows, DEV_SEED)
    train_pool, held_out = rare_target_pools()
    return {"dev id": rows, "dev ts": text_shift(rows, DEV_SEED), "dev os": shifted,
            "dev os, held-out types": [r for r in shifted if r.label.target in held_out],
            "dev os, training-pool types": [r for r in shifted if r.label.target in train_pool]}


def decide(scored: dict) -> bool:
    """decision.md: combined (augmented) >= combined (shipped) in object F1 and iRecall on each set, and
    lora (augmented) above lora (shipped) in object F1 on dev os."""
    keeps = all(scored[s]["combined (augmented)"][m] >= scored[s]["combined (shipped)"][m]
                for s in SETS for m in METRICS)
    return keeps and scored["dev os"]["lora (augmented)"]["object_f1"] > scored["dev os"]["lora (shipped)"]["object_f1"]


def main(argv: list[str]) -> int:
    from models.language import RuleParser
    from models.language.combined import CombinedParser
    from models.language.llm.parser import LoraParser, default_adapter

    ap = argparse.ArgumentParser()
    ap.add_argument("--augmented", type=Path, default=None, help="the augmented adapter folder")
    ap.add_argument("--decode-only", action="store_true", help="fill the readings caches, print no figure")
    args = ap.parse_args(argv)
    sets = dev_sets()
    rows = [r for name in SETS for r in sets[name]]
    adapters = {"shipped": default_adapter(), **({"augmented": args.augmented} if args.augmented else {})}
    rules = RuleParser()
    scored: dict[str, dict] = {name: {} for name in sets}
    for label, adapter in adapters.items():
        lm = LoraParser(adapter=adapter)
        readings = lora_readings(rows, lm, readings_cache(adapter))
        if args.decode_only:
            continue
        graphs, seconds = read_all(rows, readings, rules, {"combined": CombinedParser(lm=lm, rules=rules)})
        for name, set_rows in sets.items():
            for parser, r in score_parsers(set_rows, graphs, seconds).items():
                scored[name][parser if parser == "rules" else f"{parser} ({label})"] = r
    if args.decode_only:
        return 0
    columns = list(scored["dev id"])
    lines = [f"Development set (decision.md): {DEV_ROWS} policy rows, TS / OS with seed {DEV_SEED}; "
             "object F1 / iRecall / GED, room type given", "", *set_table(scored, scored, columns)]
    if "augmented" in adapters:
        lines += ["", f"decision rule (decision.md): {'met' if decide(scored) else 'not met'}"]
    return report(HERE / "dev.md", lines)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
