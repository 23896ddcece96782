"""Python source, for the scripts the tests run in processes of their own, that records every
compile numba starts in that process in the list ``compiled`` (the function each one compiles):
a test reads it to show that a path invoked no compiler at all."""

from __future__ import annotations

RECORD_COMPILES = """
from numba.core import event

compiled = []


class _Compiles(event.Listener):
    def on_start(self, ev):
        compiled.append(str(getattr((ev.data or {}).get("dispatcher"), "py_func", "?")))

    def on_end(self, ev):
        pass


event.register("numba:compile", _Compiles())
"""
