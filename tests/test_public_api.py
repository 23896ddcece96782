"""The top level of the package is a curated public API (types, predicates, results and
errors, families, scenes); everything else is reached through its layer."""

from __future__ import annotations

import importlib
import inspect

import quadric_contact as qc

LAYERS = ("exact", "model", "theory", "modes", "families", "scenes", "paper")


def test_every_public_name_resolves_and_is_documented():
    for name in qc.__all__:
        obj = getattr(qc, name)
        if name == "__version__":
            continue
        if inspect.isclass(obj) or inspect.isfunction(obj):
            assert inspect.getdoc(obj), f"qc.{name} has no docstring"


def test_public_names_are_defined_in_the_layers_not_at_the_top():
    for name in qc.__all__:
        obj = getattr(qc, name)
        module = getattr(obj, "__module__", None)
        if not (inspect.isclass(obj) or inspect.isfunction(obj)) or module is None:
            continue
        layer = module.split(".")[1] if module.count(".") else ""
        assert layer in LAYERS, f"qc.{name} comes from {module}, outside the layers"
        # and it is reachable where it is defined
        assert getattr(importlib.import_module(module), obj.__name__) is obj


def test_the_top_level_exports_exactly_its_all():
    exported = {n for n in vars(qc) if not n.startswith("_")}
    layers = {n for n in exported if inspect.ismodule(getattr(qc, n))}
    assert exported - layers - {"annotations"} == set(qc.__all__) - {"__version__"}


def test_tables_and_internals_come_from_their_layers():
    # the printed tables and the smallness tables are not top-level names
    for name in ("printed_table_2", "table_1", "PRINTED", "ENTRY_INDICES", "real_roots"):
        assert name not in qc.__all__
    from quadric_contact.paper.printed_tables import printed_table_2
    from quadric_contact.theory.smallness import table_1

    assert callable(printed_table_2) and callable(table_1)


def test_scenes_are_public():
    scene = qc.builtin_scene("bee_and_tree")
    assert isinstance(scene, qc.Scene)
    assert "bee_and_tree" in qc.builtin_scene_names()
