"""The bridge's routes on the studio's API server: the headset websocket, paired headsets, pushes and the
feedback export. One port for the API and the headset: the headset needs only the address the studio shows."""

from __future__ import annotations

from fastapi import FastAPI, HTTPException, Query, WebSocket
from fastapi.responses import StreamingResponse
from pydantic import BaseModel, Field

from app.bridge.export import jsonl, parse_time
from app.bridge.hub import Bridge
from studio_db import NotFound

HEADSET_PATH = "/headset"


class PushRequest(BaseModel):
    scene_id: int = Field(ge=1)
    version: int = Field(ge=1)


def mount(app: FastAPI, bridge: Bridge) -> None:
    @app.websocket(HEADSET_PATH)
    async def headset(ws: WebSocket) -> None:
        """The headset protocol (unity-bridge/protocol/README.md)."""
        await bridge.serve(ws)

    @app.get("/headsets")
    def headsets() -> list[dict]:
        return [{"session": h.session, "headset_id": h.headset_id, "device": h.device, "connected": h.connected,
                 "gloves": h.gloves} for h in bridge.paired()]

    @app.post("/headsets/{session}/push")
    def push(session: str, req: PushRequest) -> dict:
        """Send a stored scene version to a paired headset; returns the push id."""
        try:
            progress = bridge.push(session, req.scene_id, req.version)
        except NotFound as e:
            raise HTTPException(404, str(e)) from e
        except LookupError as e:
            raise HTTPException(409, str(e)) from e
        return {"push": progress.push, "steps": progress.steps}

    @app.get("/feedback")
    def feedback(format: str = Query("jsonl", pattern="^jsonl$"), since: str | None = None,
                 until: str | None = None, scene_id: int | None = None, session: str | None = None):
        """Glove feedback for retraining, one JSON record per line (README: Feedback export)."""
        for name, value in (("since", since), ("until", until)):
            try:
                parse_time(value)
            except ValueError as e:
                raise HTTPException(422, [{"loc": ["query", name], "msg": str(e)}]) from e
        return StreamingResponse(jsonl(bridge.feedback, since, until, scene_id, session),
                                 media_type="application/x-ndjson")
