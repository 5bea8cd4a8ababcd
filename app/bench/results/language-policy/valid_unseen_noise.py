"""Is the default parser's loss to the rules on valid_unseen more than the rows' noise? Read after every decision
(no policy is chosen here): each parser minus the rules on valid_unseen and its de-duplicated rows, with a 95 %
bootstrap interval over rows, from the shipped adapter's cached readings (no decoding).

    PYTHONPATH=. python app/bench/results/language-policy/valid_unseen_noise.py   # -> valid_unseen_noise.md
"""

from __future__ import annotations

import sys
from pathlib import Path

from app.bench.language import lora_readings, read_all, readings_cache

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "language-scenes"))
from design import _Cached  # noqa: E402
from run import DRAWS, interval_vs_rules  # noqa: E402  (language-scenes/run.py)


def main() -> int:
    from models.datasets.language_sets import load_language_set
    from models.language import RuleParser
    from models.language.combined import FIELDWISE, STRICT, CombinedParser
    from models.language.llm.parser import default_adapter
    rules = RuleParser()
    lines = [f"valid_unseen, each parser minus the rules, 95 % bootstrap interval over rows ({DRAWS} draws); the "
             "shipped adapter's cached readings, room type given", "",
             "| set | parser | object F1 | iRecall | GED |", "| --- | --- | --- | --- | --- |"]
    for name in ("valid_unseen", "valid_unseen_dedup"):
        rows = load_language_set(name)
        readings = lora_readings(rows, _Cached(), readings_cache(default_adapter()), progress=False)
        combined = {p: CombinedParser(rules=rules, policy=p) for p in (STRICT, FIELDWISE)}
        graphs, _ = read_all(rows, readings, rules, combined)
        for parser in ("lora", STRICT, FIELDWISE):
            cells = [interval_vs_rules(rows, graphs, parser, m, scale)
                     for m, scale in (("object_f1", 100), ("irecall", 100), ("ged", 1))]
            lines.append(f"| {name} | {parser} | " + " | ".join(f"{d:+.2f} [{lo:+.2f}, {hi:+.2f}]" for d, lo, hi in cells)
                         + " |")
    (HERE / "valid_unseen_noise.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
