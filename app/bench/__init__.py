"""Benchmarks that print figures (`h3ds bench WHAT`)."""

from __future__ import annotations


def run_benchmark(what: str, args) -> int:
    if what == "parser":
        from app.bench.parser import main
    elif what == "generate":
        from app.bench.generate import main
    elif what == "placement":
        from app.bench.placement import main
    elif what == "studio":
        from app.bench.studio import main
    elif what == "plan2place":
        from app.bench.plan2place import main
    elif what == "energy":
        from app.bench.energy import main
    elif what == "language":
        from app.bench.language import main
    elif what == "vrpose":
        from app.bench.vrpose import main
    elif what == "bridge":
        from app.bench.bridge import main
    elif what == "batch":
        from app.bench.batch import main
    elif what == "steps":
        from app.bench.steps import main
    else:
        raise ValueError(f"unknown benchmark {what!r}")
    return main(args)
