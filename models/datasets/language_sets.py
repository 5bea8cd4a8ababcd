"""The language evaluation sets of issue 10: ALFRED instructions with labelled task graphs.

Sets (models/data/language/<name>.jsonl.gz, rebuilt by `python -m models.datasets.language_sets`):
- `id_train`: ALFRED `train` minus every row whose instruction text (case and spacing folded) also
  occurs in `valid_seen` or `valid_unseen`, so no evaluation sentence is ever trained on;
- `id_eval`: ALFRED `valid_seen` (in-distribution scenes and tasks, sentences unseen in `id_train`);
- `valid_unseen`: ALFRED `valid_unseen` (unseen scenes);
- `ts`: `id_eval` rephrased by the rules of `rephrase` (text shift), label kept and re-checked;
- `os`: `id_eval` with the target object swapped for a type rare or absent as an ALFRED train target
  (object shift), by `swap_target`, label re-derived and checked.
Any name + `_dedup` drops the rows whose text occurs verbatim in ALFRED `train` (129 strings of
`valid_unseen`). Labels follow interfaces.md: `Annotation.label_graph`.
"""

from __future__ import annotations

import gzip
import json
import random
import re
from dataclasses import dataclass
from functools import cache
from importlib import resources
from pathlib import Path

from models.language.alfred import ALFRED_TYPE_NAMES, Annotation, load_annotations, named_types
from models.values import Provenance, TaskGraph, TaskObject

SET_NAMES = ("id_train", "id_eval", "valid_unseen", "ts", "os")
EVAL_SETS = ("id_eval", "valid_unseen", "valid_unseen_dedup", "ts", "os")
DATA_DIR = "data/language"
SEED = 10
# A type is "rare" as an ALFRED target when train uses it as the target at most this often (0.5 %).
RARE_TARGET_MAX = 60
# Seed of the split of the rare targets into a training pool and a held-out pool (`rare_target_pools`).
POOL_SEED = 21


@dataclass(frozen=True)
class LabelledInstruction:
    """One instruction with its room type and its labelled task graph (`label`)."""

    instruction: str
    room_type: str
    label: TaskGraph
    source: str  # "<alfred split>:<row index>" of the ALFRED row it comes from

    @property
    def task_type(self) -> str:
        return self.label.task_type

    def label_objects(self) -> set[str]:
        return {o.type for o in self.label.objects}

    def label_triplets(self) -> set[tuple[str, str, str]]:
        return {tuple(r) for r in self.label.relations}

    def roles(self) -> dict[str, set[str]]:
        return {o.type: set(o.roles) for o in self.label.objects}


def text_key(text: str) -> str:
    """Instruction text with case and spacing folded: what 'the same sentence' means for splits."""
    return " ".join(text.lower().split())


def _labelled(a: Annotation, source: str, text: str | None = None) -> LabelledInstruction:
    graph = a.label_graph() if text is None else Annotation(**{**a.__dict__, "instruction": text}).label_graph()
    graph = graph.model_copy(update={"provenance": Provenance(stage="task_graph", method="alfred-labels")})
    return LabelledInstruction(graph.instruction, a.room_type, graph, source)


# ---- text shift ----------------------------------------------------------------------------------

# Hand-picked everyday names per type (no misspellings, no near-misses such as "oven" for Microwave).
NAMES: dict[str, tuple[str, ...]] = {
    "Fridge": ("fridge", "refrigerator"), "Microwave": ("microwave", "microwave oven"),
    "CounterTop": ("counter", "countertop", "kitchen counter", "worktop"), "SinkBasin": ("sink", "basin"),
    "GarbageCan": ("trash can", "garbage can", "bin", "wastebasket", "rubbish bin"),
    "DiningTable": ("dining table", "kitchen table"), "CoffeeTable": ("coffee table",),
    "SideTable": ("side table", "end table", "nightstand"), "Cabinet": ("cabinet", "cupboard"),
    "Sofa": ("sofa", "couch"), "ArmChair": ("armchair", "arm chair"), "Dresser": ("dresser", "chest of drawers"),
    "Mug": ("mug", "coffee mug"), "RemoteControl": ("remote", "remote control", "tv remote"),
    "CellPhone": ("phone", "cell phone", "mobile phone"), "KeyChain": ("keys", "key chain", "keychain"),
    "CreditCard": ("credit card", "card"), "Laptop": ("laptop", "computer"), "Pillow": ("pillow", "cushion"),
    "AlarmClock": ("alarm clock", "clock"), "ToiletPaper": ("toilet paper", "toilet roll"),
    "Knife": ("knife", "kitchen knife"), "Potato": ("potato", "spud"), "Bread": ("bread", "loaf of bread"),
    "Lettuce": ("lettuce", "head of lettuce"), "Plate": ("plate", "dish"), "Pan": ("pan", "frying pan", "skillet"),
    "Pot": ("pot", "saucepan"), "Kettle": ("kettle", "teapot"), "DeskLamp": ("desk lamp", "table lamp"),
    "FloorLamp": ("floor lamp", "standing lamp"), "Statue": ("statue", "figurine"), "Watch": ("watch", "wristwatch"),
    "Cloth": ("cloth", "rag"), "HandTowel": ("hand towel", "towel"), "DishSponge": ("sponge", "dish sponge"),
    "TissueBox": ("tissue box", "box of tissues"), "WineBottle": ("wine bottle", "bottle of wine"),
    "Box": ("box", "cardboard box"), "TennisRacket": ("tennis racket", "racquet"),
    "BaseballBat": ("baseball bat", "bat"), "BathtubBasin": ("bathtub", "tub"), "CD": ("cd", "disc"),
    "SoapBottle": ("soap bottle", "bottle of soap"), "Cup": ("cup",), "Apple": ("apple",), "Tomato": ("tomato",),
    "Egg": ("egg",), "Bowl": ("bowl",), "Vase": ("vase",), "Book": ("book",), "Newspaper": ("newspaper",),
    "Pencil": ("pencil",), "Pen": ("pen",), "Spatula": ("spatula",), "Ladle": ("ladle",), "Spoon": ("spoon",),
    "Fork": ("fork",), "ButterKnife": ("butter knife",), "Bottle": ("glass bottle",), "Candle": ("candle",),
    "PepperShaker": ("pepper shaker",), "SaltShaker": ("salt shaker",), "Plunger": ("plunger",),
    "WateringCan": ("watering can",), "SoapBar": ("bar of soap", "soap bar"), "SprayBottle": ("spray bottle",),
    "Toilet": ("toilet",), "Bed": ("bed",), "Desk": ("desk",), "Shelf": ("shelf",), "Drawer": ("drawer",),
    "Ottoman": ("ottoman",), "Safe": ("safe",), "BasketBall": ("basketball",), "TeddyBear": ("teddy bear",),
    "Dumbbell": ("dumbbell",), "ScrubBrush": ("scrub brush",), "PaperTowelRoll": ("paper towel roll",),
    "AluminumFoil": ("aluminum foil",), "Boots": ("boots",),
}
# Word swaps that keep the meaning and the task cue (same cue class), applied as whole words.
WORD_SWAPS: dict[str, tuple[str, ...]] = {
    "put": ("place", "set", "leave"), "place": ("put", "set"), "set": ("put", "place"), "move": ("carry", "bring"),
    "pick up": ("grab", "take"), "take": ("grab", "pick up"), "grab": ("take", "pick up"), "get": ("grab", "fetch"),
    "examine": ("inspect", "look at"), "look at": ("examine", "inspect"), "inspect": ("examine",),
    "chill": ("cool",), "cool": ("chill",), "chilled": ("cooled", "cold"), "cold": ("chilled",), "cooled": ("chilled",),
    "heat": ("warm", "heat up"), "warm": ("heat",), "heated": ("warmed", "hot"), "hot": ("heated",),
    "warmed": ("heated",), "slice": ("cut",), "cut": ("slice",), "sliced": ("cut",),
    "turn on": ("switch on",), "switch on": ("turn on",), "then": ("and then", "after that"),
    "color": ("colour",), "gray": ("grey",), "center": ("centre",), "faucet": ("tap",),
}
FRAMES = ("Please {s}.", "Could you {s}?", "I'd like you to {s}.", "{S}, please.", "Can you {s} for me?",
          "Your task: {s}.", "Go and {s}.")


def _sub_word(text: str, old: str, new: str, count: int = 0) -> str:
    """`old` -> `new` as whole words (a plural ending kept), first letter's case kept, a / an agreed."""
    def keep_case(m: re.Match) -> str:
        return new[:1].upper() + new[1:] if m.group(0)[:1].isupper() else new
    out = re.sub(rf"\b{re.escape(old)}(?=(s|es)?\b)", keep_case, text, count=count, flags=re.I)
    out = re.sub(rf"\b([Aa])n? (?={re.escape(new)}\b)", lambda m: m.group(1) + ("n " if new[0] in "aeiou" else " "),
                 out)
    return out


def rephrase(text: str, rng: random.Random) -> str:
    """A rule-based paraphrase: a different everyday name for each named object (from NAMES), word
    swaps within the same meaning and task cue (WORD_SWAPS, incl. UK spellings) and a request frame."""
    out = " ".join(text.split()).rstrip(" .!")
    for names in NAMES.values():
        for name in sorted(names, key=len, reverse=True):
            if re.search(rf"\b{re.escape(name)}(s|es)?\b", out, re.I) and len(names) > 1 and rng.random() < 0.7:
                out = _sub_word(out, name, rng.choice([n for n in names if n != name]))
                break
    for old, news in WORD_SWAPS.items():
        if re.search(rf"\b{re.escape(old)}\b", out, re.I) and rng.random() < 0.6:
            out = re.sub(rf"\b{re.escape(old)}\b", rng.choice(news), out, count=1, flags=re.I)
    frame = rng.choice(FRAMES)
    s = out[:1].lower() + out[1:] if not out[:2].isupper() else out
    return frame.replace("{s}", s).replace("{S}", s[:1].upper() + s[1:])


def text_shift(rows: list[LabelledInstruction], seed: int = SEED) -> list[LabelledInstruction]:
    """Each row rephrased; a rewrite is kept only when the label derived from the new text equals the
    original label (same objects, roles, relations), else up to 5 more tries, else the row is dropped."""
    rng = random.Random(seed)
    by_source = _annotations_by_source()
    out = []
    for row in rows:
        for _ in range(6):
            text = rephrase(row.instruction, rng)
            new = _labelled(by_source[row.source], row.source, text)
            if text_key(text) != text_key(row.instruction) and _same_label(new.label, row.label):
                out.append(new)
                break
    return out


def _same_label(a: TaskGraph, b: TaskGraph) -> bool:
    return (a.task_type == b.task_type and sorted(map(tuple, a.relations)) == sorted(map(tuple, b.relations))
            and {o.type: sorted(o.roles) for o in a.objects} == {o.type: sorted(o.roles) for o in b.objects})


# ---- object shift --------------------------------------------------------------------------------

def rare_targets() -> dict[str, int]:
    """Pickupable catalogue types with a name in NAMES that ALFRED train uses as the target at most
    RARE_TARGET_MAX times (0 = never), with their train counts."""
    from models.world import catalogue
    cat = catalogue()
    counts: dict[str, int] = {}
    for a in load_annotations("train"):
        counts[a.target] = counts.get(a.target, 0) + 1
    return {t: counts.get(t, 0) for t in sorted(NAMES) if t in cat and cat.host(t).pickupable
            and counts.get(t, 0) <= RARE_TARGET_MAX}


def rare_target_pools(seed: int = POOL_SEED) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """`rare_targets()` split at random (seeded) into halves: (training pool, held-out pool). Augmented
    training data may use only the first, so the OS rows whose new target is held out show whether a
    model copies the named object or has memorised the types it was shown."""
    types = sorted(rare_targets())
    random.Random(seed).shuffle(types)
    half = len(types) // 2
    return tuple(sorted(types[:half])), tuple(sorted(types[half:]))


def sensible_targets(row: LabelledInstruction, pool: tuple[str, ...] | None = None) -> list[str]:
    """Rare targets (only those in `pool` when given) that physically fit the row's task: seen on (or
    ALFRED-valid for) the receptacle in iTHOR, fridge- or microwave-valid for cool / heat tasks,
    sliceable when sliced."""
    from models.world import catalogue
    from models.world.catalogue import load_json
    cat, valid = catalogue(), load_json("alfred_constants.json")["VAL_RECEPTACLE_OBJECTS"]

    def fits(t: str, recep: str) -> bool:
        alfred_names = {ALFRED_TYPE_NAMES.get(v, v) for v in valid.get(recep, ())}
        return cat.host(recep).contents.get(t, 0.0) > 0 or t in alfred_names

    out = []
    for t in rare_targets():
        if pool is not None and t not in pool:
            continue
        ok = not (row.label.sliced and not cat[t].flags.get("sliceable"))
        for _, rel, other in row.label.relations:
            if rel in ("placed_at", "cooled_in", "heated_in"):
                ok = ok and other in cat and fits(t, other)
            if rel == "examined_under":
                ok = ok and cat[t].mass < 5.0
        if ok and t != row.label.target:
            out.append(t)
    return out


def swap_target(row: LabelledInstruction, new: str, rng: random.Random) -> str | None:
    """The instruction with every name of the target replaced by a name of `new`, or None when the
    target is not named by a NAMES / lexicon phrase the text contains."""
    old = row.label.target
    from models.language.rule_parser import RuleParser
    phrases = [p for p, ts in RuleParser.shared().lexicon.items() if ts == (old,)] + list(NAMES.get(old, ()))
    text, hit = row.instruction, False
    for p in sorted(set(phrases), key=len, reverse=True):
        if re.search(rf"\b{re.escape(p)}(s|es)?\b", text, re.I):
            text, hit = _sub_word(text, p, rng.choice(NAMES[new])), True
    return text if hit else None


def object_shift(rows: list[LabelledInstruction], seed: int = SEED,
                 pool: tuple[str, ...] | None = None) -> list[LabelledInstruction]:
    """Rows whose named target is swapped for a sensible rare type (from `pool` when given); kept only
    when the label re-derived from the new text is the original label with the target renamed (and the
    old type no longer named)."""
    rng = random.Random(seed)
    by_source = _annotations_by_source()
    out = []
    for row in rows:
        options = sensible_targets(row, pool)
        if not options or "key" not in row.roles()[row.label.target]:
            continue
        new = rng.choice(options)
        text = swap_target(row, new, rng)
        if text is None or row.label.target in named_types(text):
            continue
        a = by_source[row.source]
        shifted = Annotation(**{**a.__dict__, "instruction": text, "object_target": new})
        got = _labelled(shifted, row.source)
        old = row.label.target
        expected = row.label.model_copy(update={
            "objects": [TaskObject(type=new if o.type == old else o.type, roles=o.roles) for o in row.label.objects],
            "relations": [tuple(new if x == old else x for x in r) for r in row.label.relations]})
        if _same_label(got.label, expected):
            out.append(got)
    return out


# ---- building and loading ------------------------------------------------------------------------

@cache
def _annotations_by_source() -> dict[str, Annotation]:
    out = {}
    for split in ("train", "valid_seen", "valid_unseen"):
        for i, a in enumerate(load_annotations(split)):
            out[f"{split}:{i}"] = a
    return out


def _alfred(split: str, exclude: set[str] = frozenset()) -> list[LabelledInstruction]:
    return [_labelled(a, f"{split}:{i}") for i, a in enumerate(load_annotations(split))
            if text_key(a.instruction) not in exclude]


def build_sets() -> dict[str, list[LabelledInstruction]]:
    """Every set from the bundled ALFRED annotations (deterministic: seeded)."""
    held_out = {text_key(a.instruction) for s in ("valid_seen", "valid_unseen") for a in load_annotations(s)}
    id_eval = _alfred("valid_seen")
    return {"id_train": _alfred("train", held_out), "id_eval": id_eval, "valid_unseen": _alfred("valid_unseen"),
            "ts": text_shift(id_eval), "os": object_shift(id_eval)}


def _encode(row: LabelledInstruction) -> dict:
    g = row.label
    return {"instruction": row.instruction, "room_type": row.room_type, "source": row.source,
            "task_type": g.task_type, "sliced": g.sliced, "objects": [[o.type, o.roles] for o in g.objects],
            "relations": [list(r) for r in g.relations]}


def _decode(d: dict) -> LabelledInstruction:
    graph = TaskGraph(instruction=d["instruction"], room_type=d["room_type"], task_type=d["task_type"],
                      sliced=d["sliced"], objects=[TaskObject(type=t, roles=r) for t, r in d["objects"]],
                      relations=[tuple(r) for r in d["relations"]],
                      provenance=Provenance(stage="task_graph", method="alfred-labels"))
    return LabelledInstruction(d["instruction"], d["room_type"], graph, d["source"])


def write_sets(out_dir: Path) -> dict[str, int]:
    out_dir.mkdir(parents=True, exist_ok=True)
    sizes = {}
    for name, rows in build_sets().items():
        body = "".join(json.dumps(_encode(r), sort_keys=True) + "\n" for r in rows).encode()
        (out_dir / f"{name}.jsonl.gz").write_bytes(gzip.compress(body, mtime=0))
        sizes[name] = len(rows)
    return sizes


@cache
def _train_texts() -> frozenset[str]:
    return frozenset(text_key(a.instruction) for a in load_annotations("train"))


@cache
def load_language_set(name: str) -> tuple[LabelledInstruction, ...]:
    """A set by name (SET_NAMES, or any of them + '_dedup': rows whose text is not verbatim in ALFRED
    train). Raises KeyError naming the known sets."""
    base = name.removesuffix("_dedup")
    if base not in SET_NAMES:
        raise KeyError(f"unknown language set {name!r}; known: {', '.join(SET_NAMES)} (each also with _dedup)")
    raw = resources.files("models").joinpath(f"{DATA_DIR}/{base}.jsonl.gz").read_bytes()
    rows = tuple(_decode(json.loads(line)) for line in gzip.decompress(raw).decode().splitlines() if line)
    if name.endswith("_dedup"):
        rows = tuple(r for r in rows if text_key(r.instruction) not in _train_texts())
    return rows


REVIEW_VERDICTS = ("ok", "S", "U", "D")  # label_review_eval.jsonl: agrees / source mismatch / under-specified / derivation
REVIEWED_SETS = ("id_eval", "valid_unseen", "ts", "os")  # every row read (each also with _dedup)


@cache
def review_verdicts() -> dict[str, tuple[str, ...]]:
    """The blind review of every evaluation label (models/data/language/label_review_eval.jsonl, procedure in
    app/bench/results/label-review/): each row's `review_key` -> the verdicts its readers gave (two for the rows
    read twice); "ok" = the label agrees with what the sentence says."""
    return parse_review(resources.files("models").joinpath(f"{DATA_DIR}/label_review_eval.jsonl").read_text())


def review_key(set_name: str, row: LabelledInstruction) -> str:
    """A row's key in `review_verdicts`: its source, prefixed with its set for `ts` and `os`, whose rows
    rewrite id_eval rows and keep their sources."""
    base = set_name.removesuffix("_dedup")
    if base not in REVIEWED_SETS:
        raise KeyError(f"the label review did not read {set_name!r}; it read {', '.join(REVIEWED_SETS)}")
    return row.source if base in REVIEWED_SETS[:2] else f"{base}:{row.source}"


def label_agrees(set_name: str, row: LabelledInstruction) -> bool:
    """Did every reader of the blind review find that `row`'s label agrees with its sentence?"""
    return all(v == "ok" for v in review_verdicts()[review_key(set_name, row)])


def parse_review(text: str) -> dict[str, tuple[str, ...]]:
    """`review_verdicts` of a review's JSON lines; an unknown verdict raises ValueError naming the row."""
    out: dict[str, tuple[str, ...]] = {}
    for line in filter(None, text.splitlines()):
        rec = json.loads(line)
        if rec["verdict"] not in REVIEW_VERDICTS:
            raise ValueError(f"label review: unknown verdict {rec['verdict']!r} for {rec['source']} "
                             f"(known: {', '.join(REVIEW_VERDICTS)})")
        out[rec["source"]] = (*out.get(rec["source"], ()), rec["verdict"])
    return out


if __name__ == "__main__":
    target = Path(__file__).resolve().parents[1] / DATA_DIR
    for set_name, n in write_sets(target).items():
        print(f"{set_name:14s} {n:6d} rows -> {target / set_name}.jsonl.gz")
