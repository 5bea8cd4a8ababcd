"""Read and write Holodeck's floor-object constraint text: `object-id | global | constraint, target | ...`.

Reading follows the rules of constraints.md: names are matched case-insensitively, a misspelled name
maps to the nearest known one when close, unknown names and missing targets are ignored, and every
such decision is reported as a warning naming the line. Nothing is dropped silently and nothing raises.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Callable

from models.constraints.language import GLOBALS, RELATIONS, Constraint, ConstraintSet, ObjectConstraints, resolve_name


def _id_key(text: str) -> str:
    return re.sub(r"[\s_]+", "-", text.strip().lower())


class _IdMatcher:
    """Finds the plan object an LLM meant by an id it may have misspelled."""

    def __init__(self, ids: list[str]):
        self.by_key = {_id_key(i): i for i in ids}

    def __call__(self, raw: str) -> tuple[str | None, bool]:
        key = _id_key(raw)
        if key in self.by_key:
            found = self.by_key[key]
            return found, found == raw.strip()
        close = difflib.get_close_matches(key, list(self.by_key), n=1, cutoff=0.85)
        return (self.by_key[close[0]], False) if close else (None, False)


def read_constraints(text: str, object_ids: list[str],
                     default_placement: Callable[[str], str] = lambda _id: "edge") -> ConstraintSet:
    """Parse constraint text for the given plan objects; objects without a line get `default_placement`."""
    match_id = _IdMatcher(object_ids)
    objects: dict[str, ObjectConstraints] = {}
    warnings: list[str] = []
    for n, line in enumerate((text or "").splitlines(), start=1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        fields = [f.strip() for f in line.split("|")]
        oid, exact = match_id(fields[0])
        if oid is None:
            warnings.append(f"line {n}: unknown object id {fields[0]!r}, line ignored")
            continue
        if not exact:
            warnings.append(f"line {n}: object id {fields[0]!r} read as {oid!r}")
        entry = objects.get(oid)
        if entry is None:
            entry = objects[oid] = ObjectConstraints(oid, default_placement(oid))
        else:
            warnings.append(f"line {n}: second line for {oid!r}, constraints merged")
        for field in fields[1:]:
            if not field:
                continue
            name_part, _, target_part = field.partition(",")
            if not target_part.strip():
                name, exact_name = resolve_name(name_part, GLOBALS)
                if name is not None:
                    if not exact_name:
                        warnings.append(f"line {n}: unknown placement {name_part.strip()!r} read as {name!r}")
                    entry.placement = name
                    continue
                relation, _ = resolve_name(name_part, RELATIONS)
                if relation is not None:
                    warnings.append(f"line {n}: constraint {relation!r} has no target, ignored")
                else:
                    warnings.append(f"line {n}: unknown constraint {name_part.strip()!r}, ignored")
                continue
            name, exact_name = resolve_name(name_part, RELATIONS)
            if name is None:
                warnings.append(f"line {n}: unknown constraint {name_part.strip()!r}, ignored")
                continue
            if not exact_name:
                warnings.append(f"line {n}: unknown constraint {name_part.strip()!r} read as {name!r}")
            target, exact_target = match_id(target_part)
            if target is None:
                warnings.append(f"line {n}: target {target_part.strip()!r} does not exist, "
                                f"constraint {name!r} ignored")
                continue
            if target == oid:
                warnings.append(f"line {n}: {oid!r} cannot be constrained to itself, constraint {name!r} ignored")
                continue
            if not exact_target:
                warnings.append(f"line {n}: target {target_part.strip()!r} read as {target!r}")
            constraint = Constraint(name, target)
            if constraint not in entry.relations:
                entry.relations.append(constraint)
    for oid in object_ids:
        objects.setdefault(oid, ObjectConstraints(oid, default_placement(oid)))
    return ConstraintSet({oid: objects[oid] for oid in object_ids}, warnings)


def write_constraints(constraints: ConstraintSet | list[ObjectConstraints]) -> str:
    items = constraints.objects.values() if isinstance(constraints, ConstraintSet) else constraints
    return "\n".join(" | ".join([oc.object_id, oc.placement, *(c.text() for c in oc.relations)]) for oc in items)


def without_object(text: str, object_id: str) -> str:
    """The text with `object_id`'s own line taken out and every constraint that targets it dropped from the other
    lines (the object left the room); the rest kept as written."""
    lines = []
    for line in (text or "").splitlines():
        fields = [f.strip() for f in line.split("|")]
        if fields[0] == object_id:
            continue
        if any(f.partition(",")[2].strip() == object_id for f in fields[1:]):
            line = " | ".join([fields[0], *(f for f in fields[1:] if f.partition(",")[2].strip() != object_id)])
        lines.append(line)
    return "\n".join(lines)
