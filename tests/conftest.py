import os

import pytest

os.environ.setdefault("HF_HUB_OFFLINE", "1")  # tests never reach a model hub
# The default parser (combined) loads a 1 GB language model at the first instruction (~9 s): tests
# that are not about parsing use the rules; the default itself is tested with H3DS_PARSER removed.
os.environ.setdefault("H3DS_PARSER", "rules")


@pytest.fixture(scope="session")
def pipeline():
    from app.pipeline import Pipeline
    return Pipeline(solver="dfs")


@pytest.fixture
def no_exact_finish(monkeypatch):
    """A repair pass alone, without the exact finish after it (Z3 over the room or a window of it, tested in
    test_exact_finish.py and test_window.py)."""
    from models.placement import exact_finish
    monkeypatch.setattr(exact_finish, "MAX_OBJECTS", 0)
    monkeypatch.setattr(exact_finish, "ONE_MORE_AT", 0)
