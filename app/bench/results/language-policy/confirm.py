"""The fresh confirmation of `rules-first-fieldwise` under the rule in decision.md (written first).

    PYTHONPATH=. python app/bench/results/language-policy/confirm.py --decode-only   # fill the readings cache
    PYTHONPATH=. python app/bench/results/language-policy/confirm.py                 # figures -> confirm.md

The fresh sets are `fresh_confirmation_sets()` (app/bench/language.py); the shipped adapter's readings
of them are appended to its cache (`readings_cache`), on one torch thread.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from app.bench.language import (FRESH_ROWS, FRESH_SEED, fieldwise_decision, fresh_confirmation_sets, lora_readings,
                                readings_cache, report, set_table)

HERE = Path(__file__).parent


def main(argv: list[str]) -> int:
    from app.bench.language import read_all, score_parsers
    from models.language import RuleParser
    from models.language.combined import FIELDWISE, POLICIES, STRICT, CombinedParser
    from models.language.llm.parser import LoraParser

    ap = argparse.ArgumentParser()
    ap.add_argument("--decode-only", action="store_true", help="fill the readings cache, print no figure")
    args = ap.parse_args(argv)
    sets = fresh_confirmation_sets()
    rows = [r for s in sets.values() for r in s]
    lm = LoraParser(threads=1)
    readings = lora_readings(rows, lm, readings_cache(lm.adapter))
    if args.decode_only:
        return 0
    rules = RuleParser()
    combined = {p: CombinedParser(lm=lm, rules=rules, policy=p) for p in POLICIES}
    graphs, seconds = read_all(rows, readings, rules, combined)
    scored = {k: score_parsers(v, graphs, seconds) for k, v in sets.items()}
    columns = ["rules", "lora", *POLICIES]
    met = fieldwise_decision(scored, FIELDWISE, STRICT)
    lines = [f"Fresh confirmation sets (decision.md): {FRESH_ROWS} id_train rows drawn with seed {FRESH_SEED}, "
             f"TS / OS rewritten with seed {FRESH_SEED}; object F1 / iRecall / GED, room type given", "",
             *set_table(scored, scored, columns, ged_digits=3)]
    lines += ["", f"decision rule (decision.md), {FIELDWISE} as the default policy: {'met' if met else 'not met'}"]
    return report(HERE / "confirm.md", lines)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
