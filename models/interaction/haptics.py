"""Haptic profiles: what the TactGlove plays and how it is tinted when the person touches an object.

The class comes from the object's AI2-THOR properties, as in the paper (pickupable, isHeatSource,
isColdSource, mass): a heat source is `hot`, a cold source `cold`, a lamp or light switch `light`
(AI2-THOR has no light-source flag; these are the toggle targets of ALFRED's look-at-in-light task),
anything else `normal`. Mass and pickupable set how hard the glove vibrates: a light pickupable object
gives a soft grasp, a heavy one a strong grasp that the wrist motor also carries (its weight); an object
that cannot be picked up gives a fingertip touch only.

Colours (linear RGB): cooling black -> blue and light black -> white are the paper's. Hot is black ->
orange (1.0, 0.45, 0.0): the warm end of the usual thermal scale, and orange-vs-blue is the contrast
pair that the common colour-vision deficiencies (protan, deutan) keep, where red-vs-green is lost.
"""

from __future__ import annotations

import math

from models.values import Scene, SceneObject
from models.values.interaction import GLOVE_MOTORS, ColourTransition, HapticProfile, MotorPattern
from models.world import catalogue

BLACK = (0.0, 0.0, 0.0)
COLOURS: dict[str, tuple[tuple[float, float, float], int, str]] = {
    # class: (end colour, transition ms, name)
    "hot": ((1.0, 0.45, 0.0), 1500, "black -> orange (heating)"),
    "cold": ((0.0, 0.35, 1.0), 1500, "black -> blue (cooling)"),
    "light": ((1.0, 1.0, 1.0), 1000, "black -> white (brightness)"),
    "normal": (BLACK, 0, "black (no change)"),
}
STATE_WHY = {"cold": "state: cooled inside a closed fridge", "hot": "state: heated inside a microwave while on"}
LIGHT_TYPES = frozenset({"FloorLamp", "DeskLamp", "LightSwitch", "Candle"})
# Share of the grasp intensity each motor gets: the thumb and index carry a grasp, the little finger least.
GRASP_SHARE = (1.0, 0.9, 0.75, 0.6, 0.45)
HEAVY_KG = 3.0  # from this mass on the grasp is at full strength
TOUCH_MS = 120
GRASP_MS = {"hot": 150, "cold": 400, "light": 120, "normal": 250}
PULSES = {"hot": 3, "cold": 2, "light": 1, "normal": 1}
GAP_MS = {"hot": 80, "cold": 200, "light": 0, "normal": 0}


def haptic_class(type_name: str) -> tuple[str, str]:
    """(class, why) from the type's AI2-THOR properties."""
    cat = catalogue()
    if type_name not in cat:
        return "normal", f"{type_name} is not in the AI2-THOR catalogue"
    flags = cat.host(type_name).flags
    if flags["isHeatSource"]:
        return "hot", "isHeatSource"
    if flags["isColdSource"]:
        return "cold", "isColdSource"
    if type_name in LIGHT_TYPES:
        return "light", "a light source (toggleable lamp or switch)"
    return "normal", "no heat, cold or light source"


def grasp_strength(type_name: str) -> tuple[int, str]:
    """Peak grasp intensity 0-100 from mass (pickupable objects) and a note on why."""
    cat = catalogue()
    if type_name not in cat or not cat.host(type_name).pickupable:
        return 0, "not pickupable: touch only"
    mass = max(cat.host(type_name).mass, 0.0)
    strength = 35 + 65 * min(1.0, math.log1p(mass) / math.log1p(HEAVY_KG))
    return int(round(strength)), f"pickupable, {mass:g} kg"


def profile_for(object_id: str, scene_object_id: str, type_name: str, cls: str | None = None) -> HapticProfile:
    """The profile of one object; `cls` overrides the class (an object the robot has cooled is cold)."""
    natural, why = haptic_class(type_name)
    if cls is not None and cls != natural:
        why = STATE_WHY.get(cls, f"state: {cls}")
    cls = cls or natural
    strength, weight_note = grasp_strength(type_name)
    temperature = {"hot": 25, "cold": 15}.get(cls, 0)  # temperature is felt as extra tip vibration
    tip = min(100, 30 + temperature)
    touch = MotorPattern(intensities=[0, tip, 0, 0, 0, 0], duration_ms=TOUCH_MS)
    if strength:
        fingers = [min(100, int(round(strength * s)) + temperature) for s in GRASP_SHARE]
        wrist = int(round(strength * 0.5))
    else:
        fingers = [min(100, int(round(tip * s))) for s in GRASP_SHARE]
        wrist = 0
    grasp = MotorPattern(intensities=fingers + [wrist], duration_ms=GRASP_MS[cls], pulses=PULSES[cls],
                         gap_ms=GAP_MS[cls])
    end, ms, name = COLOURS[cls]
    return HapticProfile(object_id=object_id, scene_object_id=scene_object_id, object_type=type_name,
                         haptic_class=cls, touch=touch, grasp=grasp,
                         colour=ColourTransition(start=BLACK, end=end, duration_ms=ms, name=name),
                         why=f"{why}; {weight_note}")


def state_class(cooled: bool, heated: bool) -> str | None:
    """The class an object's task state gives it (ALFRED's cooled / heated flags), or None for its nature.
    The headset side switches an object's profile to this when the robot has cooled or heated it."""
    return "hot" if heated else "cold" if cooled else None


def house_id(obj: SceneObject, child: bool, room: int = 1) -> str:
    """The id the ProcTHOR export gives a scene object (models.exports.procthor_house.thor_id)."""
    from models.exports.procthor_house import thor_id
    return thor_id(obj, child, room)


def haptic_profiles(scene: Scene, room: int = 1) -> list[HapticProfile]:
    """One profile per object of the scene, children included, keyed by the exported house id (`room`: the
    number the house gives the scene's room)."""
    out = []
    for o in scene.objects:
        out.append(profile_for(house_id(o, False, room), o.id, o.type))
        out.extend(profile_for(house_id(c, True, room), c.id, c.type) for c in o.children)
    return out


def readme_table() -> str:
    """The README's table of haptic classes, generated from this module (tests/test_haptics.py checks the
    README holds exactly this)."""
    examples = (("Microwave", None), ("Fridge", None), ("Bread", "cold"), ("Apple", "hot"), ("FloorLamp", None),
                ("Candle", None), ("Egg", None), ("Apple", None), ("Pot", None), ("Sofa", None))
    names = " / ".join(GLOVE_MOTORS)
    lines = ["| class | AI2-THOR rule | example (mass) | touch (hover) | grasp (select): " + names + " | "
             "grasp timing | glove colour |", "| --- | --- | --- | --- | --- | --- | --- |"]
    for type_name, state in examples:
        p = profile_for(type_name, type_name, type_name, state)
        rule, weight = p.why.rsplit("; ", 1)
        timing = f"{p.grasp.pulses} x {p.grasp.duration_ms} ms" + (f", {p.grasp.gap_ms} ms gap" if p.grasp.pulses > 1 else "")
        colour = f"{p.colour.name}, {p.colour.duration_ms} ms" if p.colour.duration_ms else p.colour.name
        lines.append(f"| {p.haptic_class} | {rule} | {type_name} ({weight}) | index {p.touch.intensities[1]}, "
                     f"{p.touch.duration_ms} ms | {' / '.join(map(str, p.grasp.intensities))} | {timing} | {colour} |")
    return "\n".join(lines)

