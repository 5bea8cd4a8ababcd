"""The studio's Placement tab: the placer's steps replayed in the 3D view (play / pause / step / show all at a chosen
speed), each step's candidates as a heat-map on the floor, and the energy terms after each step as a plot.

The replay shows each step where the placer made it (frontend.replay); in an apartment it goes room by room and
each caption names the room. The steps and how many are shown live in the session's state, so an edit that re-places
the room starts the replay afresh."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

import numpy as np

from frontend.captions import step_caption
from frontend.replay import RoomOf, energy_after_steps, room_at
from models.placement import PlacementStep
from models.values import ConstraintPlan

ENERGY_TERMS = ("rel", "collision", "oob", "nav", "aff", "missing", "total")  # the plot's series
ENERGY_COLOURS = ("#e07b39", "#c0392b", "#8e44ad", "#2980b9", "#27ae60", "#7f8c8d", "#111111")
ENERGY_DECIMALS = 4  # the plot's resolution
ENERGY_PLOT_TOP = 1.0  # the plot's y axis shows at least 0..1 (a layout of energy 0 draws flat, not magnified)


class PlacementPanel:
    def __init__(self, session, gui):
        self.session = session
        buttons = gui.add_button_group("Animation", ("Play", "Pause", "Step", "Show all"))
        buttons.on_click(lambda e: self.animate(e.target.value))
        self.speed = gui.add_slider("Objects / s", 0.5, 10.0, 0.5, 3.0)
        self.step_md = gui.add_markdown("")
        self.heat = gui.add_checkbox("Candidate heat-map", True)
        self.energy_plot = gui.add_uplot(
            data=(np.zeros(1), *[np.zeros(1) for _ in ENERGY_TERMS]),
            series=({"label": "step"}, *[{"label": t, "stroke": c} for t, c in zip(ENERGY_TERMS, ENERGY_COLOURS)]),
            title="Energy terms per step", aspect=1.6, scales={"x": {"time": False}})

    def animate(self, command: str) -> None:
        s = self.session
        if s.displayed() is None:
            return
        if command in ("Play", "Step") and s.state.shown >= len(s.state.steps):
            s.state.shown = 0  # from the start again
            s.redraw()
        s.state.playing = command == "Play"
        if command == "Play":
            threading.Thread(target=self._play, daemon=True).start()
        elif command == "Step":
            self.advance()
        elif command == "Show all":
            s.state.shown = len(s.state.steps)
            s.redraw()
            self.step_md.content = "All objects shown."

    def _play(self) -> None:
        s = self.session
        while s.state.playing and not s.closed and s.state.shown < len(s.state.steps):
            self.advance()
            time.sleep(max(0.0, 1.0 / float(self.speed.value) - 0.25))
        s.state.playing = False

    def next_step(self) -> tuple[PlacementStep, int] | None:
        """Move the animation on by one step and show its candidates' heat-map: (the step, how many steps are shown
        now), or None at the end."""
        s = self.session
        with s.lock:
            if s.state.shown >= len(s.state.steps):
                return None
            step = s.state.steps[s.state.shown]
            s.state.shown += 1
            shown = s.state.shown
        if self.heat.value:
            s.view.heat_map(step)
        return step, shown

    def advance(self) -> None:
        """Show the next step: heat-map of its candidates, then the object settling into the pose the step gave it
        (at its last step, where it stands now: the designer may have moved it since; frontend.replay)."""
        s = self.session
        if (next_step := self.next_step()) is None:
            return
        (step, shown), steps = next_step, s.state.steps
        scene, room_of, start = s.displayed(), s.room_of(), None
        (before, was), (after, now) = room_at(scene, steps, shown - 1, room_of), room_at(scene, steps, shown, room_of)
        if step.restart:  # the room solved again from empty
            s.view.hide(was - ({o.id for o in scene.all_objects()} if now is None else now))
        obj = next((o for o in after.objects if o.id == step.object_id), None) if step.x is not None else None
        if not step.restart and step.object_id in was:
            start = next(o for o in before.objects if o.id == step.object_id)
        room = s.apartment.where(step) if s.apartment.current is not None else ""
        self.step_md.content = step_caption(steps, shown, obj, room, room_of)
        if obj is None:
            return
        frames = max(2, min(8, int(20 / float(self.speed.value))))  # fewer frames when playing fast
        duration = min(0.25, 0.8 / float(self.speed.value))
        for k in range(1, frames + 1):
            if s.closed:
                return
            s.view.settle(obj, k / frames, start)
            time.sleep(duration / frames)
        if shown == len(steps):
            s.view.heat_map(None)

    def energy_curve(self, rooms: list[tuple[ConstraintPlan, list]], steps: list[PlacementStep], room_of: RoomOf,
                     current: Callable[[], bool]) -> None:
        """The energy terms after each placement step of the room (or the apartment's rooms, summed) as the animation
        shows it then (frontend.replay.energy_after_steps); drawn when ready if what it is of is `current`."""
        rows = energy_after_steps(rooms, steps, room_of)
        if not current() or not rows:
            return
        xs = np.arange(1, len(rows) + 1, dtype=float)
        # rounded: a term's float noise (1e-17 where it is 0) would otherwise set the plot's scale
        series = [np.round([r[t] for r in rows], ENERGY_DECIMALS) for t in ENERGY_TERMS]
        top = max(ENERGY_PLOT_TOP, 1.1 * float(np.max(series)))
        self.energy_plot.scales = {"x": {"time": False}, "y": {"range": (0.0, top)}}
        self.energy_plot.data = (xs, *series)
