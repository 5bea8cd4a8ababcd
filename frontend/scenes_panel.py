"""The studio's Scenes tab: accept & save (as a new stored scene or its next version), the stored scenes and their
versions, reopening one, and downloads (house JSON, GLB) named after the version.

Saving runs the checks first: a scene that fails some is saved only once the designer confirms, and the override
is stored as an edit. An apartment on screen is checked room by room and saved by its own mode (frontend.apartment)."""

from __future__ import annotations

import contextlib
import json
from dataclasses import replace

from app.pipeline import Generation, generation_of
from frontend.captions import slug
from models.checks import Finding
from models.exports.stored import glb_of, house_of
from models.placement import SOLVERS
from models.values import Scene
from models.values.apartment import Apartment
from models.values.edit import Edit


class ScenesPanel:
    def __init__(self, session, gui):
        self.session = session
        self.save_name = gui.add_text("Name", "")
        gui.add_button("Accept & save", color="blue").on_click(lambda _: self.accept())
        self.stored = gui.add_dropdown("Stored scene", ("-",))
        self.stored.on_update(lambda _: self.list_versions())
        self.version = gui.add_dropdown("Version", ("-",))
        gui.add_button("Open").on_click(lambda _: self.open_version())
        gui.add_button("Refresh list").on_click(lambda _: self.list_scenes())
        gui.add_button("Download house JSON").on_click(lambda _: self.download("house"))
        gui.add_button("Download GLB").on_click(lambda _: self.download("glb"))
        gui.add_markdown("Downloads are the selected stored version (the scene on screen if none is "
                         "stored yet), named `<scene>-v<n>-house.json` and `<scene>-v<n>.glb`.")

    def accept(self) -> None:
        """Save the scene (or the apartment, every room checked) on screen; one that fails a check asks first."""
        s = self.session
        if s.apartment.current is not None:
            findings, save, what = s.apartment.findings(), s.apartment.save, "an apartment"
        elif s.state.gen is not None:
            findings, save, what = s.refresh_checks(), self._save, "a scene"
        else:
            s.say("**Error:** Nothing to save yet: generate a scene first.")
            return
        if findings:
            listed = "\n".join(f"- ⚠ {f.text}" for f in findings)
            s.confirm(f"Save {what} that fails {len(findings)} check(s)?",
                      f"{listed}\n\nSaving anyway records that the checks were overridden.",
                      "Save anyway", lambda: save(findings))
            return
        save([])

    def _save(self, overridden: list[Finding]) -> None:
        s = self.session
        gen = s.state.gen
        name = self.save_name.value.strip() or gen.task_graph.instruction[:60]
        sid, number = self.store_version(name, gen.scene, self.edits_with(overridden))
        s.state.values = replace(s.state.values, edits=())
        s.say(f"Saved as scene {sid}, version {number} (“{name}”)"
              + (f", overriding {len(overridden)} failed check(s)." if overridden else "."))

    def edits_with(self, overridden: list[Finding]) -> list[Edit]:
        """The designer's edits to store with a version, and the checks saved over, if any."""
        edits = list(self.session.state.edits)
        if overridden:
            edits.append(Edit("override", "checks", [f.text for f in overridden], "saved anyway"))
        return edits

    def store_version(self, name: str, value: Scene | Apartment, edits: list[Edit]) -> tuple[int, int]:
        """Store as a new scene, or as the next version of the stored scene on screen; select it in the
        list. Returns (scene id, version number)."""
        s = self.session
        state, store = s.state, s.store
        if state.scene_id is None:
            sid, number = store.create_scene(name, value, state.seed, state.solver, edits)
            state.scene_id = sid
        else:
            sid = state.scene_id
            number = store.add_version(sid, name, value, state.seed, state.solver, edits)
        self.list_scenes(select=(sid, number))
        s.set_unsaved(False)
        return sid, number

    def list_scenes(self, select: tuple[int, int] | None = None) -> None:
        scenes = self.session.store.list_scenes()
        self.stored.options = tuple(f"{s['id']}: {s['name'][:50]}" for s in scenes) or ("-",)
        if select is not None:
            self.stored.value = next(o for o in self.stored.options if o.split(":")[0] == str(select[0]))
        self.list_versions(select[1] if select else None)

    def list_versions(self, number: int | None = None) -> None:
        sid = self.selected()[0]
        versions = self.session.store.versions(sid) if sid is not None else []
        self.version.options = tuple(f"v{v['number']}: {v['name'][:40]}" for v in versions) or ("-",)
        if versions:
            self.version.value = next((o for o in self.version.options if o.startswith(f"v{number}:")),
                                      self.version.options[-1])

    def selected(self) -> tuple[int | None, int | None]:
        """The stored scene and version selected in the lists (None where nothing is)."""
        scene, version = self.stored.value, self.version.value
        return (int(scene.split(":")[0]) if scene and scene != "-" else None,
                int(version.split(":")[0].removeprefix("v")) if version and version != "-" else None)

    def open_version(self) -> None:
        s = self.session
        sid, number = self.selected()
        if sid is None or number is None:
            s.say("**Error:** No stored scene selected.")
            return
        scene = s.store.scene(sid, number)
        stored = s.store.versions(sid)[number - 1]
        if isinstance(scene, Apartment):
            self._use_stored_settings(stored)
            s.apartment.open(scene, sid, number, stored)
            return
        try:
            gen = generation_of(scene)
        except ValueError as e:
            s.say(f"**Error:** {e}")
            return
        self._use_stored_settings(stored)
        with s.busy("Opening the stored scene") as free:
            if not free:
                return
            s.run(lambda observer: self._replayable(gen, observer), fresh=True)
        s.state.scene_id = sid
        s.set_unsaved(False)
        s.instruction.value = gen.task_graph.instruction
        s.say(f"Opened scene {sid}, version {number}: {len(gen.layout.placements)} objects. The Placement "
              f"tab replays the placer re-run with the stored seed ({stored['seed']}) and solver "
              f"(`{stored['solver']}`); each object lands at its stored pose.")

    def _use_stored_settings(self, stored: dict) -> None:
        """The Task tab's seed and solver become the stored version's (the replay uses them)."""
        s = self.session
        s.seed.value = stored["seed"]
        if stored["solver"] in SOLVERS:
            s.solver.value = stored["solver"]

    def _replayable(self, gen: Generation, observer) -> Generation:
        """A stored scene has no recorded steps: re-run its placer with the seed of its layout (the stored seed, or
        the next one the placer kept where a layout cut a door off) for the order and candidates of each step; the
        stored layout (with the designer's moves) stays what is shown."""
        s = self.session
        with contextlib.suppress(Exception):  # a solver that no longer exists: the scene opens without replay
            s.pipeline.place(gen.plan, gen.layout.seed, s.solver.value, observer)
        return gen

    def download(self, kind: str) -> None:
        """The selected stored version, named after it; the scene on screen when nothing is stored."""
        s = self.session
        sid, number = self.selected()
        if s.apartment.current is not None and (sid is None or number is None):
            value = s.apartment.current
            stem = f"{slug(value.task_graph.instruction)}-apartment-unsaved"
        elif sid is not None and number is not None:
            value = s.store.scene(sid, number)
            name = next((x["name"] for x in s.store.list_scenes() if x["id"] == sid), f"scene-{sid}")
            stem = f"{slug(name) or f'scene-{sid}'}-v{number}"
        elif s.state.gen is not None:
            value, stem = s.state.gen.scene, f"{slug(s.state.gen.task_graph.instruction)}-unsaved"
        else:
            s.say("**Error:** Nothing to download: generate or open a scene first.")
            return
        if kind == "house":
            s.client.send_file_download(f"{stem}-house.json", json.dumps(house_of(value), indent=2).encode(),
                                        save_immediately=True)
        else:
            s.client.send_file_download(f"{stem}.glb", glb_of(value), save_immediately=True)
        s.say(f"Downloaded `{stem}` ({'house JSON' if kind == 'house' else 'GLB'}).")
