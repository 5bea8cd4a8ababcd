"""Apartment -> ProcTHOR house JSON and GLB of the whole house.

House JSON as ProcTHOR writes a multi-room house: every room's walls are cut where a neighbour starts
or ends; a stretch shared by two rooms is written once per room (`wall|2|...` and `wall|3|...`, same
coordinates) and a door between them names both rooms (room0, room1) and both walls (wall0, wall1);
an outside stretch has its `wall|exterior|...` twin, which the entrance and the windows are cut into.
Objects are in the house frame, their ids carry their room's number (`Fridge|2|0`). Hole offsets are
measured from each wall's first point (its lower-coordinate end, as in the single-room export).
"""

from __future__ import annotations

from models.exports.procthor_house import (
    _wall_id,
    hole,
    metadata,
    point_light,
    procedural_parameters,
    room_entry,
    thor_object,
    wall_entry,
)
from models.planning.floorplan import WallPiece, wall_pieces
from models.scene.apartment import shifted
from models.values import Opening
from models.values.apartment import OUTSIDE, Apartment, HouseRoom
from models.world.catalogue import load_json


def _num(room_id: str) -> str:
    return room_id.split("|")[-1]


def _seg(p: WallPiece) -> tuple[float, float, float, float]:
    return p.x0, p.z0, p.x1, p.z1


def _walls(apartment: Apartment, pieces: list[WallPiece], height: float) -> list[dict]:
    materials = {hr.id: hr.room.wall_material for hr in apartment.floorplan.rooms}
    out = [wall_entry(_wall_id(_num(p.room), _seg(p)), p.room, _seg(p), height, materials[p.room]) for p in pieces]
    out += [wall_entry(_wall_id("exterior", _seg(p)), "exterior", _seg(p), height, materials[p.room])
            for p in pieces if p.other == OUTSIDE]
    return out


def _doors(apartment: Apartment) -> list[dict]:
    out = []
    for d in apartment.floorplan.doors:
        seg = (d.x0, d.z0, d.x1, d.z1)
        inside = [r for r in d.rooms if r != OUTSIDE]
        rooms = (inside[0], inside[-1])
        walls = (_wall_id(_num(rooms[0]), seg),
                 _wall_id("exterior" if OUTSIDE in d.rooms else _num(rooms[1]), seg))
        height = load_json("structure.json")["doors"][d.asset_id]["height"]
        opening = Opening(wall="south", center=d.center, width=d.width, asset_id=d.asset_id, height=height, sill=0.0)
        entry = hole(d.id, opening, rooms, walls, d.center)
        entry.update(openable=True, openness=1)
        out.append(entry)
    return out


def _piece_of(hr: HouseRoom, o: Opening, pieces: list[WallPiece]) -> tuple[WallPiece, float]:
    """The outside piece of the room's wall that holds the opening, and the opening's offset along it."""
    horizontal = o.wall in ("south", "north")
    at = (hr.x if horizontal else hr.z) + o.center
    for p in pieces:
        start, end = (p.x0, p.x1) if horizontal else (p.z0, p.z1)
        if p.room == hr.id and p.wall == o.wall and p.other == OUTSIDE and start <= at <= end:
            return p, at - start
    raise ValueError(f"{hr.id}: the window at {o.center} on the {o.wall} wall is not on an outside wall")


def _windows(apartment: Apartment, pieces: list[WallPiece]) -> list[dict]:
    out = []
    for hr in apartment.floorplan.rooms:
        for n, o in enumerate(hr.room.windows):
            piece, along = _piece_of(hr, o, pieces)
            walls = (_wall_id(_num(hr.id), _seg(piece)), _wall_id("exterior", _seg(piece)))
            out.append(hole(f"window|{_num(hr.id)}|{n}", o, (hr.id, hr.id), walls, along))
    return out


def apartment_house(apartment: Apartment) -> dict:
    rooms = apartment.floorplan.rooms
    pieces = wall_pieces({hr.id: hr.bounds for hr in rooms})
    height = max(hr.room.wall_height or 2.6 for hr in rooms)
    objects = [thor_object(shifted(o, hr), room=int(_num(hr.id)))
               for hr, scene in zip(rooms, apartment.scenes) for o in scene.objects]
    lights = [point_light(f"light_{_num(hr.id)}", hr.x + hr.room.width / 2, height - 0.2, hr.z + hr.room.depth / 2)
              for hr in rooms]
    return {
        "rooms": [room_entry(hr.id, hr.room, [(x0, z0), (x0, z1), (x1, z1), (x1, z0)])
                  for hr in rooms for x0, z0, x1, z1 in [hr.bounds]],
        "walls": _walls(apartment, pieces, height),
        "doors": _doors(apartment),
        "windows": _windows(apartment, pieces),
        "objects": objects,
        "proceduralParameters": procedural_parameters(lights),
        "metadata": metadata(apartment.robot_start, f"h3ds-apartment-{len(rooms)}-rooms"),
    }


def apartment_glb(apartment: Apartment) -> bytes:
    from models.exports.glb import house_glb  # trimesh takes ~0.6 s to import
    rooms = apartment.floorplan.rooms
    return house_glb([(hr.room, hr.x, hr.z, f"{hr.room.type.replace(' ', '-')}-{_num(hr.id)}-") for hr in rooms],
                     [shifted(o, hr) for hr, s in zip(rooms, apartment.scenes) for o in s.objects])
