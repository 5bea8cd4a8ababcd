"""The Task tab's "Correct the task graph" folder: a designer sets an object's role, adds or removes an object type,
then regenerates the room (or the whole apartment, whose rooms and their objects the graph decides) from the graph.
Each correction is undoable and stored as an edit; nothing is placed again until Regenerate."""

from __future__ import annotations

from dataclasses import replace

from app.pipeline import Generation
from models.values import TaskObject
from models.values.edit import Edit
from models.world import catalogue

ROLE_CHOICES = ("key", "anchor", "inference", "key + anchor", "anchor + inference")


class GraphPanel:
    def __init__(self, session, gui):
        self.session = session
        self.object = gui.add_dropdown("Object", ("-",))
        self.role = gui.add_dropdown("Role", ROLE_CHOICES)
        gui.add_button("Set role").on_click(lambda _: self.set_role())
        self.new_object = gui.add_text("Add object type", "")
        gui.add_button("Add object").on_click(lambda _: self.add_object())
        gui.add_button("Remove object").on_click(lambda _: self.remove_object())
        self.regenerate_button = gui.add_button("Regenerate from graph")
        self.regenerate_button.on_click(lambda _: self.regenerate())

    def update(self) -> None:
        """Follow the graph on screen: its object types in the dropdown."""
        self.object.options = tuple(o.type for o in self.session.state.gen.task_graph.objects) or ("-",)

    def _edit(self, objects: list[TaskObject], note: str) -> None:
        s = self.session
        gen = s.state.gen
        kept = {o.type for o in objects}  # a relation naming a removed object goes with it
        graph = gen.task_graph.model_copy(update={"objects": objects, "relations": [
            r for r in gen.task_graph.relations if r[0] in kept and r[2] in kept]})
        edit = Edit("task-graph", note, [o.model_dump() for o in gen.task_graph.objects],
                    [o.model_dump() for o in objects])
        s.history.record(f"task graph {note}", s.state.values)
        s.state.values = replace(s.state.values, gen=Generation(graph, gen.room_plan, gen.plan, gen.layout, gen.scene),
                                 edits=s.state.edits + (edit,))
        s.refresh_panels()
        s.set_unsaved(True)
        s.say(f"Task graph edited ({note}). Press **Regenerate from graph** to rebuild the "
              f"{'apartment' if s.apartment.current else 'room'}.")

    def set_role(self) -> None:
        gen = self.session.state.gen
        if gen is None:
            return
        roles = [r.strip() for r in self.role.value.split("+")]
        objects = [TaskObject(type=o.type, roles=roles) if o.type == self.object.value else o
                   for o in gen.task_graph.objects]
        self._edit(objects, f"{self.object.value} -> {self.role.value}")

    def add_object(self) -> None:
        gen = self.session.state.gen
        if gen is None:
            return
        try:
            found = catalogue().object_type(self.new_object.value)
        except ValueError as e:
            self.session.say(f"**Error:** {str(e)[0].upper()}{str(e)[1:]}.")
            return
        self._edit(gen.task_graph.objects + [TaskObject(type=found, roles=["inference"])], f"+{found}")

    def remove_object(self) -> None:
        gen = self.session.state.gen
        if gen is None:
            return
        self._edit([o for o in gen.task_graph.objects if o.type != self.object.value], f"-{self.object.value}")

    def regenerate(self) -> None:
        """The room (or apartment) again from the corrected graph, with the same seed and solver; undoable."""
        s = self.session
        gen = s.state.gen
        if gen is None:
            return
        with s.busy("Regenerating from the corrected graph") as free:
            if not free:
                return
            graph = gen.task_graph
            if s.apartment.current is not None:
                s.apartment.regenerate(graph)
                return
            s.run(lambda obs: s.pipeline.generate_from_graph(graph, s.state.seed, s.state.solver, obs),
                  fresh=False, record="regenerate from graph")
