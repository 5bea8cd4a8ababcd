"""Hand-built scenes for the interaction tests (VR pose, haptics, robot plan): fixed poses, real assets."""

from __future__ import annotations

from models.values import AgentPose, Opening, Room, Scene, SceneObject, Size, TaskGraph, TaskObject
from models.world import catalogue


def obj(oid: str, type_name: str, x: float, z: float, rotation: float = 0.0, role: str = "context",
        children: tuple[SceneObject, ...] = (), y: float | None = None) -> SceneObject:
    asset = catalogue().host(type_name).assets[0]
    w, h, d = asset.size
    return SceneObject(id=oid, type=type_name, asset_id=asset.asset_id, role=role, x=x, y=h / 2 if y is None else y,
                       z=z, rotation=rotation, size=Size(x=w, y=h, z=d), children=list(children))


def on(parent_height: float, oid: str, type_name: str, x: float, z: float, role: str = "context") -> SceneObject:
    asset = catalogue().host(type_name).assets[0]
    return obj(oid, type_name, x, z, role=role, y=parent_height + asset.size[1] / 2)


def graph(task_type: str, relations: list[tuple[str, str, str]], roles: dict[str, list[str]],
          sliced: bool = False, room_type: str = "kitchen") -> TaskGraph:
    return TaskGraph(instruction=f"test {task_type}", room_type=room_type, task_type=task_type,
                     objects=[TaskObject(type=t, roles=r) for t, r in roles.items()], relations=relations, sliced=sliced)


def kitchen(task: TaskGraph, drop: tuple[str, ...] = ()) -> Scene:
    """A 5 m x 5 m kitchen, door in the south wall: counter along the north wall carrying bread, a knife and a
    microwave; a fridge on the east wall; a dining table in the middle with an apple; a sink basin on the west
    wall; a floor lamp in the south-west. `drop` leaves objects of these types out."""
    counter_h = catalogue().host("CounterTop").assets[0].size[1]
    table_h = catalogue().host("DiningTable").assets[0].size[1]
    key_types = {o.type: ("anchor" if "anchor" in o.roles else "inference" if "inference" in o.roles else "key")
                 for o in task.objects}
    role = lambda t: key_types.get(t, "context")  # noqa: E731
    counter_kids = tuple(c for c in (on(counter_h, "bread-0", "Bread", 1.0, 4.6, role("Bread")),
                                     on(counter_h, "knife-0", "Knife", 1.6, 4.6, role("Knife")),
                                     on(counter_h, "microwave-0", "Microwave", 2.4, 4.6, role("Microwave")),
                                     on(counter_h, "creditcard-0", "CreditCard", 0.6, 4.6, role("CreditCard")))
                         if c.type not in drop)
    objects = [obj("countertop-0", "CounterTop", 1.6, 4.6, 180, role("CounterTop"), counter_kids),
               obj("fridge-0", "Fridge", 4.55, 2.5, 270, role("Fridge")),
               obj("diningtable-0", "DiningTable", 2.5, 2.5, 0, role("DiningTable"),
                   (on(table_h, "apple-0", "Apple", 2.5, 2.5, role("Apple")),)),
               obj("sinkbasin-0", "SinkBasin", 0.4, 2.5, 90, role("SinkBasin")),
               obj("floorlamp-0", "FloorLamp", 0.4, 0.5, 0, role("FloorLamp"))]
    objects = [o for o in objects if o.type not in drop]
    room = Room(type="kitchen", width=5.0, depth=5.0, doors=[Opening(wall="south", center=2.5, width=1.0)])
    return Scene(id="test-kitchen", room=room, task_graph=task, objects=objects,
                 robot_start=AgentPose(x=2.5, z=0.6, rotation=0))


COOL = graph("pick_cool_then_place_in_recep", [("Bread", "cooled_in", "Fridge"), ("Bread", "placed_at", "CounterTop")],
             {"Bread": ["key"], "Fridge": ["inference"], "CounterTop": ["key", "anchor"]})
HEAT_SLICED = graph("pick_heat_then_place_in_recep",
                    [("Apple", "sliced_with", "Knife"), ("Apple", "heated_in", "Microwave"),
                     ("Apple", "placed_at", "SinkBasin")],
                    {"Apple": ["key"], "Knife": ["inference"], "Microwave": ["inference"],
                     "SinkBasin": ["key", "anchor"]}, sliced=True)
SIMPLE = graph("pick_and_place_simple", [("Apple", "placed_at", "CounterTop")],
               {"Apple": ["key"], "CounterTop": ["key", "anchor"]})
LOOK = graph("look_at_obj_in_light", [("CreditCard", "examined_under", "FloorLamp")],
             {"CreditCard": ["key"], "FloorLamp": ["key", "anchor"]})
LAMP_ONLY = graph("look_at_obj_in_light", [], {"FloorLamp": ["key", "anchor"]})  # the parsers' "Turn on the lamp"
