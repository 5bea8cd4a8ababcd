"""Writes the headset protocol's JSON Schema files (v1/*.schema.json), one per message type.

The files are the contract: the studio and the headset simulator validate against them, the Unity
package is written against them. The scene push embeds the studio's value types (VR pose, haptic
profiles, robot plan) as their pydantic JSON Schemas, so the two cannot drift apart.
Run: `python unity-bridge/protocol/generate.py` (tests/test_protocol.py checks the files are current).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

VERSION = 1
HERE = Path(__file__).resolve().parent
OUT = HERE / f"v{VERSION}"
BASE_URI = f"https://h3ds.studio/protocol/v{VERSION}/"

ID = {"type": "string", "minLength": 1, "maxLength": 64}
SHORT = {"type": "string", "maxLength": 200}
HANDS = ["left", "right"]
FINGERS = ["thumb", "index", "middle", "ring", "little", "palm"]
HAPTIC = ["hot", "cold", "light", "normal"]
DEFS: dict[str, dict] = {}  # shared definitions of the embedded value types
RGB = {"type": "array", "items": {"type": "number", "minimum": 0, "maximum": 1}, "minItems": 3, "maxItems": 3}


def obj(props: dict, required: list[str] | None = None) -> dict:
    return {"type": "object", "properties": props, "required": list(props) if required is None else required,
            "additionalProperties": False}


def envelope_props() -> dict:
    return {
        "version": {"const": VERSION, "description": "protocol version; a different one is refused"},
        "type": {"type": "string", "description": "the message type (one schema file per type)"},
        "session": {"type": "string", "maxLength": 64,
                    "description": "the headset's session id (chosen by the headset at hello, kept across "
                                   "reconnects); glove events are de-duplicated by (session, seq)"},
        "id": {**ID, "description": "message id, unique per sender (a UUID); acks and errors name it"},
        "seq": {"type": "integer", "minimum": 0,
                "description": "sender's sequence number in this session, +1 per message, never reset on "
                               "reconnect; a resent message keeps its seq"},
        "ts": {"type": "number", "description": "sender's clock when the message was first made, Unix seconds"},
        "body": {"type": "object"},
    }


def bodies() -> dict[str, tuple[str, str, dict]]:
    """type -> (direction, what it is for, body schema)."""
    sys.path.insert(0, str(HERE.parents[1]))
    from models.values.interaction import HapticProfile, RobotPlan, VRPoseChoice

    def schema_of(model) -> dict:
        """The model's schema; its $defs move to the message's root, where its '#/$defs/...' refs point."""
        schema = model.model_json_schema(mode="serialization")
        DEFS.update(schema.pop("$defs", {}))
        return schema

    scene_ref = obj({"push": {**ID, "description": "the id of the scene_push message this happened in"}})
    return {
        "hello": ("both", "Headset: first message after connecting. Studio: its reply (limits, versions).", obj({
            "role": {"enum": ["headset", "studio"]},
            "device": {**SHORT, "description": "e.g. 'Meta Quest 3' or 'h3ds headset simulator (stand-in)'"},
            "app_version": SHORT,
            "capabilities": {"type": "array", "items": {"type": "string", "maxLength": 40}, "maxItems": 32,
                             "description": "e.g. ai2thor, hand-tracking, bhaptics, passthrough"},
            "gloves": obj({h: {"type": "boolean"} for h in HANDS}),
            "max_message_bytes": {"type": "integer", "minimum": 1024,
                                  "description": "studio reply: the largest headset message it accepts"},
        }, ["role", "device"])),
        "pair": ("headset->studio", "Pair with the token the studio shows, or resume with the key it gave.", {
            **obj({"token": {"type": "string", "pattern": "^[0-9]{6}$"},
                   "resume_key": {"type": "string", "minLength": 16, "maxLength": 128}}, []),
            "oneOf": [{"required": ["token"]}, {"required": ["resume_key"]}]}),
        "paired": ("studio->headset", "Pairing accepted; keep resume_key to reconnect after a drop.", obj({
            "headset_id": ID, "resume_key": {"type": "string", "minLength": 16, "maxLength": 128},
            "studio": SHORT,
            "last_seq": {"type": "integer", "minimum": 0,
                         "description": "highest headset seq the studio has stored for this session (0: none)"},
        })),
        "scene_push": ("studio->headset", "A stored scene version to load, with everything to run it.", obj({
            "push": {**ID, "description": "push id; later messages about this scene name it"},
            "scene_id": {"type": "integer"}, "version": {"type": "integer"}, "name": SHORT,
            "instruction": {"type": "string", "maxLength": 1000},
            "house": {"type": "object", "description": "ProcTHOR house JSON, verbatim (for CreateHouse)"},
            "vr_start_pose": schema_of(VRPoseChoice),
            "haptic_profiles": {"type": "array", "items": schema_of(HapticProfile)},
            "robot_plan": schema_of(RobotPlan),
        })),
        "scene_loaded": ("headset->studio", "The house is built (CreateHouse succeeded).", obj({
            **scene_ref["properties"], "load_ms": {"type": "number", "minimum": 0},
            "objects": {"type": "integer", "minimum": 0}}, ["push"])),
        "scene_failed": ("headset->studio", "The house could not be built; reason says why.", obj({
            **scene_ref["properties"], "reason": {"type": "string", "maxLength": 2000}})),
        "plan_step_result": ("headset->studio", "The robot ran one step of the plan.", obj({
            **scene_ref["properties"], "index": {"type": "integer", "minimum": 0},
            "of": {"type": "integer", "minimum": 1, "description": "steps in the plan"},
            "action": {"type": "string", "maxLength": 60}, "ok": {"type": "boolean"},
            "message": {"type": "string", "maxLength": 2000}}, ["push", "index", "of", "action", "ok"])),
        "glove_event": ("headset->studio", "A hand met an object (Meta XR hover/select, bHaptics played).", obj({
            **scene_ref["properties"],
            "t": {"type": "number", "minimum": 0, "description": "seconds since the scene loaded"},
            "object_id": {"type": "string", "minLength": 1, "maxLength": 200,
                          "description": "the object's id in the house JSON"},
            "object_type": {"type": "string", "minLength": 1, "maxLength": 80},
            "kind": {"enum": ["hover", "unhover", "select", "unselect"]},
            "hand": {"enum": HANDS},
            "fingers": {"type": "array", "items": {"enum": FINGERS}, "maxItems": 6, "uniqueItems": True,
                        "description": "fingers in contact (HandGrabInteractor.GrabbingFingers or the poke tip)"},
            "haptic_class": {"enum": HAPTIC},
            "intensity": {"type": "integer", "minimum": 0, "maximum": 100, "description": "peak motor intensity played"},
            "glove_colour": {**RGB, "description": "the glove tint after the event, linear RGB 0-1"},
        }, ["push", "t", "object_id", "object_type", "kind", "hand", "fingers", "haptic_class", "intensity",
            "glove_colour"])),
        "user_decision": ("headset->studio", "The person accepts or rejects the scene.", obj({
            **scene_ref["properties"], "decision": {"enum": ["accept", "reject"]},
            "comment": {"type": "string", "maxLength": 2000}}, ["push", "decision"])),
        "ping": ("both", "Liveness; answered by pong.", obj({})),
        "pong": ("both", "Answer to ping.", obj({"ping": ID})),
        "ack": ("both", "The message `of` was handled (for glove events: its record is committed).", obj({
            "of": ID, "seq": {"type": "integer", "minimum": 0},
            "duplicate": {"type": "boolean", "description": "already stored before (a resend); not stored again"},
        }, ["of", "seq"])),
        "error": ("both", "A message was refused; code and message say why.", obj({
            "code": {"enum": ["malformed", "unknown_type", "bad_version", "invalid", "too_large", "unpaired",
                              "wrong_token", "unknown_push", "internal"]},
            "message": {"type": "string", "maxLength": 2000},
            "of": {"type": ["string", "null"], "description": "id of the refused message, when it had one"},
            "fatal": {"type": "boolean", "description": "the sender closes the connection after this"},
        }, ["code", "message"])),
        "session_end": ("both", "The session is over (the headset leaves, or the studio unpairs it).", obj({
            "reason": SHORT})),
    }


def message_schema(kind: str, direction: str, doc: str, body: dict) -> dict:
    props = envelope_props()
    props["type"] = {"const": kind}
    props["body"] = body
    schema = {"$schema": "https://json-schema.org/draft/2020-12/schema", "$id": f"{BASE_URI}{kind}.schema.json",
              "title": kind, "description": f"{doc} Direction: {direction}.", "type": "object",
              "properties": props, "required": list(props), "additionalProperties": False}
    if '"#/$defs/' in json.dumps(body):
        schema["$defs"] = dict(sorted(DEFS.items()))
    return schema


def schemas() -> dict[str, dict]:
    """file name -> schema, the envelope first."""
    env = {"$schema": "https://json-schema.org/draft/2020-12/schema", "$id": f"{BASE_URI}envelope.schema.json",
           "title": "envelope", "description": "Every message: a JSON object with these fields, one per websocket "
                                               "text frame.", "type": "object", "properties": envelope_props(),
           "required": list(envelope_props()), "additionalProperties": False}
    out = {"envelope.schema.json": env}
    for kind, (direction, doc, body) in bodies().items():
        out[f"{kind}.schema.json"] = message_schema(kind, direction, doc, body)
    return out


def render(schema: dict) -> str:
    return json.dumps(schema, indent=2, sort_keys=False) + "\n"


if __name__ == "__main__":
    OUT.mkdir(exist_ok=True)
    for name, schema in schemas().items():
        (OUT / name).write_text(render(schema))
    print(f"wrote {len(schemas())} schemas to {OUT}")
