"""The protocol's schema files: current with their generator, valid JSON Schema, and the studio's parser
refuses what they refuse."""

import importlib.util
import json
from pathlib import Path

import pytest
from jsonschema import Draft202012Validator

from app.bridge.protocol import SCHEMA_DIR, ProtocolError, message, parse, validators

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("protocol_generate", ROOT / "unity-bridge/protocol/generate.py")
generate = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(generate)

GLOVE = {"push": "p1", "t": 1.5, "object_id": "Bread|surface|3|1", "object_type": "Bread", "kind": "select",
         "hand": "right", "fingers": ["thumb", "index"], "haptic_class": "cold", "intensity": 60,
         "glove_colour": [0.0, 0.35, 1.0]}


def test_committed_schemas_are_what_the_generator_writes():
    made = generate.schemas()
    on_disk = {p.name for p in SCHEMA_DIR.glob("*.schema.json")}
    assert on_disk == set(made), "run: python unity-bridge/protocol/generate.py"
    for name, schema in made.items():
        assert (SCHEMA_DIR / name).read_text() == generate.render(schema), f"{name} is stale; regenerate it"
        Draft202012Validator.check_schema(schema)


def test_every_message_type_has_a_schema_and_a_row_in_the_readme():
    readme = (ROOT / "unity-bridge/protocol/README.md").read_text()
    for kind in validators():
        assert f"| `{kind}` |" in readme


def test_a_valid_glove_event_parses_and_each_defect_is_named():
    msg = message("glove_event", "s1", 1, GLOVE)
    assert parse(json.dumps(msg))["body"]["object_id"] == GLOVE["object_id"]
    cases = {
        "malformed": "[1, 2",
        "unknown_type": json.dumps({**msg, "type": "glove"}),
        "bad_version": json.dumps({**msg, "version": 0}),
        "invalid": json.dumps({**msg, "body": {**GLOVE, "intensity": 101}}),
        "too_large": json.dumps({**msg, "body": {**GLOVE, "object_id": "x" * 70000}}),
    }
    for code, frame in cases.items():
        with pytest.raises(ProtocolError) as e:
            parse(frame)
        assert e.value.code == code and e.value.message
    with pytest.raises(ProtocolError, match="intensity"):
        parse(cases["invalid"])
    with pytest.raises(ProtocolError, match="extra"):
        parse(json.dumps({**msg, "body": {**GLOVE, "extra": 1}}))
