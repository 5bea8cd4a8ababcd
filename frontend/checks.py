"""The checks line of the studio's Constraints tab (the checks themselves: models.checks)."""

from __future__ import annotations

from models.checks import Finding


def summary(findings: list[Finding]) -> str:
    """Markdown for the checks line: a green tick or the list of problems."""
    if not findings:
        return "**Checks:** ✓ no collisions, everything in the room, doorway and robot start free, " \
               "task objects reachable, no metric dropped."
    return "**Checks: ⚠ " + f"{len(findings)} problem(s)**\n\n" + "\n".join(f"- ⚠ {f.text}" for f in findings)
