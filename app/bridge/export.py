"""Feedback export for retraining: one JSON object per line per stored glove event (fields: README,
"Feedback export"), shared by `h3ds feedback export` and GET /feedback."""

from __future__ import annotations

import json
from datetime import datetime, timezone
from typing import Iterator

from studio_db.feedback import FeedbackStore


def parse_time(text: str | None) -> datetime | None:
    """ISO 8601 (a date or a date and time; UTC when no zone is given) or None."""
    if not text:
        return None
    try:
        d = datetime.fromisoformat(text)
    except ValueError:
        raise ValueError(f"not an ISO 8601 time: {text!r} (e.g. 2026-11-22 or 2026-11-22T18:00:00Z)") from None
    return d if d.tzinfo else d.replace(tzinfo=timezone.utc)


def jsonl(feedback: FeedbackStore, since: str | None = None, until: str | None = None,
          scene_id: int | None = None, session: str | None = None) -> Iterator[str]:
    start, end = parse_time(since), parse_time(until)
    for record in feedback.records(start, end, scene_id, session):
        yield json.dumps(record, ensure_ascii=False) + "\n"
