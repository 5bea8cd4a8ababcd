"""The studio's Constraints tab: an object's constraints as a list, dropdowns to add one or remove its relations,
the plan's raw constraint text, and the layout's metrics; in an apartment, those of the room edited.

Every edit goes through the raw text (models.constraints reads and writes it): a text that does not read is not
applied and its problems are listed; one that removes every relation asks first. An applied edit re-plans from the
first object it touches (Pipeline.replan), undoable and stored as an edit."""

from __future__ import annotations

import contextlib
from dataclasses import replace

from app.pipeline import kept_before_edit
from models.constraints import GLOBALS, RELATIONS, Constraint, read_constraints, write_constraints
from models.placement.problem import plan_constraints
from models.values.edit import Edit


class _Rejected(Exception):
    pass


class ConstraintsPanel:
    def __init__(self, session, gui):
        self.session = session
        self.scope = gui.add_markdown("")
        self.room = gui.add_dropdown("Room edited", ("-",), visible=False, hint="in an apartment: the room whose "
                                     "constraints, drags and re-places these tools edit")
        self.room.on_update(self._choose_room)
        self.object = gui.add_dropdown("Object", ("-",))
        self.object.on_update(lambda _: self.show())
        self.listing = gui.add_markdown("")
        self.kind = gui.add_dropdown("Constraint", GLOBALS + RELATIONS, initial_value="near")
        self.target = gui.add_dropdown("Target", ("-",))
        gui.add_button("Add constraint").on_click(lambda _: self.add())
        gui.add_button("Remove its relations").on_click(lambda _: self.clear_relations())
        self.text = gui.add_text("Raw constraints", "", multiline=True)
        gui.add_button("Apply text").on_click(lambda _: self.apply_text(self.text.value))
        self.message = gui.add_markdown("")
        self.metrics = gui.add_markdown("")

    def update(self) -> None:
        """Follow the scene on screen: its objects in the dropdowns, its plan's text, the selected object's list."""
        s = self.session
        plan = s.state.gen.plan
        apartment = s.apartment.current
        self.scope.content = (f"Editing **{s.apartment.label()}** of the apartment; a click on an object in another "
                              "room edits that room." if apartment is not None else "")
        if apartment is not None:
            self.room.options = tuple(s.apartment.label(k) for k in range(len(apartment.plans)))
            self.room.value = s.apartment.label()
        self.room.visible = apartment is not None
        ids = tuple(o.id for o in plan.objects) or ("-",)
        self.object.options = self.target.options = ids
        self.text.value = plan.constraints
        self.show()

    def _choose_room(self, event) -> None:
        """The Room edited dropdown, as the designer sets it: its room becomes the one edited (not while an edit is
        being placed: the dropdown goes back), and an object picked in another room is let go."""
        s = self.session
        if event.client is None or s.apartment.current is None or self.room.value not in self.room.options:
            return  # set by `update`, or nothing to choose from
        s.apartment.focus_room(self.room.options.index(self.room.value))
        self.room.value = s.apartment.label()
        if s.picking.selected is not None and not s.picking.movable():
            s.picking.pick(None)

    def select(self, object_id: str) -> None:
        """Show `object_id`'s constraints (a click on it in the 3D view)."""
        self.object.value = object_id
        self.show()

    def show(self) -> None:
        gen = self.session.state.gen
        if gen is None or self.object.value not in {o.id for o in gen.plan.objects}:
            return
        cs = plan_constraints(gen.plan)
        oc = cs.objects[self.object.value]
        items = [f"- `{oc.placement}`"] + [f"- `{c.name}` → `{c.target}`" for c in oc.relations]
        self.listing.content = f"**{oc.object_id}**\n\n" + "\n".join(items)

    def apply_text(self, text: str) -> None:
        s = self.session
        gen = s.state.gen
        if gen is None:
            return
        ids = [o.id for o in gen.plan.objects]
        cs = read_constraints(text, ids)
        if cs.warnings:
            self.message.content = "**Error:** Edit not applied:\n\n" + "\n".join(f"- {w}" for w in cs.warnings)
            return
        had = sum(len(oc.relations) for oc in read_constraints(gen.plan.constraints, ids).objects.values())
        if had and not any(oc.relations for oc in cs.objects.values()):
            s.confirm("Remove all constraints?",
                      f"This edit removes all {had} relations between objects and re-places the room.",
                      "Remove them", lambda: self._replan(text))
            return
        self._replan(text)

    def _replan(self, text: str) -> None:
        s = self.session
        gen = s.state.gen
        with s.busy("Re-placing after the constraint edit") as free:
            if not free:
                return
            kept = kept_before_edit(gen, gen.plan.model_copy(update={"constraints": text}))
            edit = Edit("constraints", "plan", gen.plan.constraints, text)
            if not s.run(lambda obs: s.pipeline.replan(gen, text, s.state.seed, s.state.solver, obs),
                         fresh=False, record="constraint edit", keep_reference=True):
                return
            s.state.values = replace(s.state.values, edits=s.state.edits + (edit,))
        moved = [p.id for p in s.state.gen.layout.placements
                 if (q := gen.layout.placement(p.id)) is None or (q.x, q.z, q.rotation) != (p.x, p.z, p.rotation)]
        self.message.content = (f"Re-placed after the edit ({len(kept)} objects before the edited one kept); "
                                f"moved: {', '.join(moved) or 'nothing'}.")

    def _edit_object(self, change) -> None:
        gen = self.session.state.gen
        if gen is None or self.object.value not in {o.id for o in gen.plan.objects}:
            return
        cs = read_constraints(gen.plan.constraints, [o.id for o in gen.plan.objects])
        change(cs.objects[self.object.value])
        self.apply_text(write_constraints(cs))

    def add(self) -> None:
        name, target = self.kind.value, self.target.value

        def change(oc):
            if name in GLOBALS:
                oc.placement = name
            elif target == oc.object_id:
                self.message.content = "**Error:** An object cannot be constrained to itself."
                raise _Rejected
            else:
                oc.relations.append(Constraint(name, target))
        with contextlib.suppress(_Rejected):
            self._edit_object(change)

    def clear_relations(self) -> None:
        self._edit_object(lambda oc: oc.relations.clear())
