import os

import pytest

os.environ.setdefault("HF_HUB_OFFLINE", "1")  # tests never reach a model hub


@pytest.fixture(scope="session")
def pipeline():
    from app.pipeline import Pipeline
    return Pipeline(solver="dfs")
