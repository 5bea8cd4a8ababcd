"""The HTTP service: generate scenes, store accepted versions, list and export them.

A thin shell over `app.pipeline` and `studio_db`; request bodies are validated models, so bad input
gets a 422 that names the field. OpenAPI docs are served at /docs.
"""

from __future__ import annotations

import dataclasses
import json
from typing import Annotated

from fastapi import FastAPI, HTTPException, Query, Response
from fastapi.responses import StreamingResponse
from pydantic import AfterValidator, BaseModel, Field, model_validator

from app.bridge import bridge_for, mount
from app.editing import MAX_EDITS, EditError, EditStep, apply_edits
from app.pipeline import Generation, Pipeline, dump, outside, strangers
from models.exports.apartment import apartment_house
from models.exports.stored import glb_of, house_of
from models.language import InstructionError, check_instruction
from models.placement import DEFAULT_SOLVER, SOLVERS
from models.placement.base import summaries
from models.placement.stepping import TOP, step_record
from models.planning.apartment_planner import ApartmentError, is_apartment, parse_rooms
from models.planning.floorplan import FloorplanError
from models.values import ConstraintPlan, Scene
from models.values.apartment import APARTMENT, Apartment
from models.values.edit import Edit
from models.world import INFER, ROOM_TYPES, requested_room_type
from studio_db import NotFound, Store
from studio_db.store import Stored, WrongKind


NDJSON = "application/x-ndjson"
MAX_TOP = 100_000  # candidates a step record may list: every candidate of a step, for a floor heat-map


def _known_solver(name: str) -> str:
    if name not in SOLVERS:
        raise ValueError(f"unknown solver {name!r}; available: {', '.join(sorted(SOLVERS))}")
    return name


class GenerateRequest(BaseModel):
    """The checks are the CLI's: their ValueErrors become 422s naming the field."""

    instruction: Annotated[str, Field(min_length=1, max_length=1000, examples=["Put a chilled bread on the counter"]),
                           AfterValidator(check_instruction)]
    room_type: Annotated[str, Field(examples=["kitchen"]), AfterValidator(_room_type)]
    seed: int = Field(0, ge=0, le=2**31 - 1)
    solver: Annotated[str, AfterValidator(_known_solver)] = DEFAULT_SOLVER
    rooms: Annotated[list[str] | None, Field(max_length=100, examples=[["kitchen", "living room", "bedroom"]]),
                     AfterValidator(parse_rooms)] = None  # room_type "apartment" only


class PlaceRequest(BaseModel):
    """A constraint plan to place (interfaces.md), with poses to keep as they are (`h3ds place --keep`)."""

    plan: ConstraintPlan
    seed: int = Field(0, ge=0, le=2**31 - 1)
    solver: Annotated[str, AfterValidator(_known_solver)] = DEFAULT_SOLVER
    keep: dict[str, tuple[float, float, float]] = Field(default_factory=dict, examples=[{"fridge-0": [0.4, 0.4, 0]}])

    @model_validator(mode="after")
    def _kept_are_its_objects(self) -> PlaceRequest:
        if unknown := strangers(self.plan, self.keep):
            raise ValueError(f"keep: not objects of plan {self.plan.id}: {', '.join(unknown)}")
        if far := outside(self.plan, self.keep):
            raise ValueError(f"keep: {far}")
        return self


def _room_type(name: str) -> str:
    return APARTMENT if is_apartment(name) else requested_room_type(name) or INFER


class EditIn(BaseModel):
    kind: str = Field(min_length=1, max_length=40)
    target: str = Field(min_length=1, max_length=200)
    before: object = None
    after: object = None


class SceneOrApartment(BaseModel):
    """A single room (`scene`) or an apartment (`apartment`), as POST /generate returns them: exactly one."""

    scene: Scene | None = None
    apartment: Apartment | None = None

    @model_validator(mode="after")
    def _one_value(self) -> SceneOrApartment:
        if (self.scene is None) == (self.apartment is None):
            raise ValueError("give exactly one of scene (a single room) and apartment")
        return self

    @property
    def value(self) -> Stored:
        return self.scene or self.apartment


class AcceptRequest(SceneOrApartment):
    name: str = Field(min_length=1, max_length=200)
    seed: int = Field(0, ge=0)
    solver: str = Field(DEFAULT_SOLVER, min_length=1, max_length=40)
    edits: list[EditIn] = Field(default_factory=list)


class EditRequest(SceneOrApartment):
    """Edits of a scene as POST /generate returned it or GET /scenes/.../versions/N gives it back; in an apartment,
    the number of the `room` edited (from 1, as the floorplan's `room|N`; left out: the room of the object the first
    edit names)."""

    room: int | None = Field(None, ge=1, examples=[2])
    edits: list[EditStep] = Field(min_length=1, max_length=MAX_EDITS)
    seed: int | None = Field(None, ge=0, le=2**31 - 1)  # the scene's own when left out
    solver: Annotated[str, AfterValidator(_known_solver)] = DEFAULT_SOLVER


def _findings(found) -> list[dict]:
    return [{"kind": f.kind, "text": f.text, "objects": list(f.objects)} for f in found]


def _single(gen: Generation) -> dict:
    return {k: json.loads(dump(getattr(gen, k))) for k in ("task_graph", "plan", "layout", "scene")}


def _apartment(apartment: Apartment) -> dict:
    return {"task_graph": json.loads(dump(apartment.task_graph)), "apartment": json.loads(dump(apartment)),
            "house": apartment_house(apartment)}


def create_app(store: Store, pipeline: Pipeline | None = None) -> FastAPI:
    pipeline = pipeline or Pipeline()
    app = FastAPI(title="H3DS Studio API", version="0.1.0",
                  description="Instruction -> AI2-THOR scene; stored scenes, versions and exports.")

    def scene_or_404(scene_id: int, number: int | None = None) -> Stored:
        try:
            return store.scene(scene_id, number)
        except NotFound as e:
            raise HTTPException(404, str(e)) from e

    @app.get("/health")
    def health() -> dict:
        return {"status": "ok", "database": store.location.split("@")[-1]}

    @app.get("/solvers")
    def solvers() -> dict:
        """The placers a request may name as its `solver`, each with a line on what it does, and the default."""
        return {"default": DEFAULT_SOLVER, "solvers": summaries()}

    @app.get("/room-types")
    def room_types() -> dict:
        """What POST /generate takes as `room_type`: a single room's type, "infer" (the parser reads it from the
        instruction) or "apartment" (several rooms joined by doors; `rooms` names them)."""
        return {"room_types": list(ROOM_TYPES), "infer": INFER, "apartment": APARTMENT}

    @app.post("/generate")
    def generate(req: GenerateRequest) -> dict:
        """Run the whole pipeline; nothing is stored until the scene is accepted. For room_type "apartment":
        the task graph, the apartment (floorplan, rooms' plans, layouts and scenes, robot path) and its house JSON."""
        if req.rooms is not None and req.room_type != APARTMENT:
            raise HTTPException(422, [{"loc": ["body", "rooms"], "msg": "rooms needs room_type apartment"}])
        try:
            if req.room_type == APARTMENT:
                return _apartment(pipeline.generate_apartment(req.instruction, req.rooms, req.seed, req.solver))
            gen = pipeline.generate(req.instruction, req.room_type, seed=req.seed, solver=req.solver)
        except InstructionError as e:
            raise HTTPException(422, [{"loc": ["body", "instruction"], "msg": str(e)}]) from e
        except (ApartmentError, FloorplanError) as e:
            raise HTTPException(422, [{"loc": ["body", "rooms"], "msg": str(e)}]) from e
        return _single(gen)

    @app.post("/place")
    def place(req: PlaceRequest) -> dict:
        """Place a plan's objects (the layout JSON of interfaces.md); the `keep` poses (object id -> x, z,
        rotation) stay as they are and the rest is placed around them."""
        return json.loads(dump(pipeline.place(req.plan, req.seed, req.solver, keep=req.keep or None)))

    @app.post("/edit")
    def edit(req: EditRequest) -> dict:
        """The studio's edits, in order: `move` an object, edit the `constraints` text (placed again from the first
        object it changes), `replace_around` named objects. Nothing is stored: the answer has POST /generate's
        shape plus `edits` (the log to store with POST /scenes) and `findings` (the checks the studio runs before
        saving; a single room's metric drops are against the scene sent)."""
        try:
            done = apply_edits(pipeline, req.value, req.edits, req.room, req.seed, req.solver)
        except EditError as e:
            raise HTTPException(422, [{"loc": ["body", *e.loc], "msg": str(e)}]) from e
        log = [dataclasses.asdict(e) for e in done.log]
        shape = _apartment(done.value) if req.apartment else _single(done.room)
        return {**shape, "edits": log, "findings": _findings(done.findings)}

    @app.post("/place/steps", response_class=StreamingResponse,
              responses={200: {"content": {NDJSON: {}}, "description": "one JSON object per line"}})
    def place_steps(req: PlaceRequest, top: Annotated[int, Query(ge=0, le=MAX_TOP)] = TOP) -> StreamingResponse:
        """`POST /place` step by step, as the placer makes each step: one JSON line per step (`h3ds place --steps`:
        pose, energy terms, reason, `restart`, and the `top` best candidates with their scores, Plan2Place's the
        policy's probabilities), then `{"layout": ...}`; a solver that fails ends the stream with `{"error": ...}`."""
        stepping = pipeline.stepping(req.plan, req.seed, req.solver, keep=req.keep or None)

        async def lines():  # the placer runs in Stepping's thread, each step handed to the server's event loop
            k = 0
            try:
                async for step in stepping:
                    k += 1
                    yield json.dumps(step_record(step, k, top)) + "\n"
            except Exception as e:  # the status line is sent already: the stream's last line says what failed
                yield json.dumps({"error": f"{type(e).__name__}: {e}"}) + "\n"
                return
            yield json.dumps({"layout": json.loads(dump(stepping.layout))}) + "\n"
        return StreamingResponse(lines(), media_type=NDJSON)

    @app.post("/scenes", status_code=201)
    def accept(req: AcceptRequest) -> dict:
        """Store a scene (a single room or an apartment) as a new scene with version 1."""
        edits = [Edit(e.kind, e.target, e.before, e.after) for e in req.edits]
        scene_id, number = store.create_scene(req.name, req.value, req.seed, req.solver, edits)
        return {"scene_id": scene_id, "version": number}

    @app.post("/scenes/{scene_id}/versions", status_code=201)
    def accept_version(scene_id: int, req: AcceptRequest) -> dict:
        """Store a scene as the next version of an existing scene of the same kind (409 otherwise)."""
        edits = [Edit(e.kind, e.target, e.before, e.after) for e in req.edits]
        try:
            number = store.add_version(scene_id, req.name, req.value, req.seed, req.solver, edits)
        except NotFound as e:
            raise HTTPException(404, str(e)) from e
        except WrongKind as e:
            raise HTTPException(409, str(e)) from e
        return {"scene_id": scene_id, "version": number}

    @app.get("/scenes")
    def list_scenes() -> list[dict]:
        return store.list_scenes()

    @app.get("/scenes/{scene_id}")
    def get_scene(scene_id: int) -> dict:
        try:
            return {"scene_id": scene_id, "versions": store.versions(scene_id), "edits": store.edits(scene_id)}
        except NotFound as e:
            raise HTTPException(404, str(e)) from e

    @app.get("/scenes/{scene_id}/versions/{number}")
    def get_version(scene_id: int, number: int) -> dict:
        """The stored Scene, or the stored Apartment (floorplan, rooms' plans, layouts and scenes)."""
        return json.loads(scene_or_404(scene_id, number).model_dump_json(exclude_none=True))

    @app.get("/scenes/{scene_id}/versions/{number}/house.json")
    def export_house(scene_id: int, number: int) -> dict:
        """ProcTHOR house JSON (an apartment's with all its rooms)."""
        return house_of(scene_or_404(scene_id, number))

    @app.get("/scenes/{scene_id}/versions/{number}/scene.glb")
    def export_glb(scene_id: int, number: int) -> Response:
        return Response(glb_of(scene_or_404(scene_id, number)), media_type="model/gltf-binary",
                        headers={"Content-Disposition": f'attachment; filename="scene-{scene_id}-v{number}.glb"'})

    @app.get("/scenes/{scene_id}/versions/{number}/layout.json")
    def export_layout(scene_id: int, number: int) -> dict:
        from app.pipeline import generation_of
        stored = scene_or_404(scene_id, number)
        if isinstance(stored, Apartment):
            raise HTTPException(409, f"scene {scene_id} is an apartment: its layouts (one per room) are in "
                                     f"GET /scenes/{scene_id}/versions/{number}")
        try:
            return json.loads(dump(generation_of(stored).layout))
        except ValueError as e:
            raise HTTPException(409, str(e)) from e

    mount(app, bridge_for(store))  # the headset websocket, pushes and the feedback export
    return app
