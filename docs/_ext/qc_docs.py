"""Pages of the documentation that are made from the package itself at build time.

* ``_generated/errata_table.md`` and ``_generated/errata_entries.md``: the errata registry
  :data:`quadric_contact.paper.errata.ERRATA`, as a table and entry by entry (included by
  ``departures.md`` and ``errata.md``), so the site cannot disagree with the registry.
* ``notebooks/*.ipynb``: copies of the teaching notebooks of ``notebooks/`` (which Sphinx
  cannot read outside its source folder), rendered by myst-nb with their outputs.
* Cross-references to a name the package re-exports (``quadric_contact.Quadric``, defined
  in ``quadric_contact.model.quadric``) resolve to where the name is documented, when the
  name really exists: a reference to a name that does not is left to fail the build.
"""

from __future__ import annotations

import importlib
import shutil
import types
import typing
from pathlib import Path
from typing import Any

from sphinx import addnodes
from sphinx.transforms.post_transforms import SphinxPostTransform
from sphinx.util import logging

logger = logging.getLogger(__name__)

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent


def _plain(text: str) -> str:
    """The registry's text as Markdown that shows it as written: ``-27*c0**2*c3**4`` is a
    formula, not emphasis, and ``$`` no mathematics."""
    for char in "\\`*_[]<>$":
        text = text.replace(char, "\\" + char)
    return text


def _cell(text: str) -> str:
    return _plain(" ".join(text.split())).replace("|", "\\|")


def errata_table() -> str:
    from quadric_contact.paper.errata import ERRATA

    lines = [
        "| key | where | corrected |",
        "| --- | --- | --- |",
    ]
    for e in ERRATA:
        lines.append(f"| {{ref}}`{e.key} <{e.key}>` | {_cell(e.location)} | {_cell(e.corrected)} |")
    return "\n".join(lines) + "\n"


def errata_entries() -> str:
    from quadric_contact.paper.errata import ERRATA

    out = [f"The registry holds {len(ERRATA)} errata.\n"]
    for e in ERRATA:
        out.append(f"({e.key})=\n## `{e.key}`\n")
        out.append(f"**Where.** {_plain(e.location)}\n")
        out.append(f"**Printed.** {_plain(e.printed)}\n")
        out.append(f"**Corrected.** {_plain(e.corrected)}\n")
        out.append(f"**Evidence.** {_plain(e.evidence)}\n")
        out.append(f"**Consequence.** {_plain(e.consequence)}\n")
        if e.confidence:
            out.append(f"**Confidence that the printed paper is wrong.** {_plain(e.confidence)}\n")
    return "\n".join(out)


def _defined_in(name: str, obj: Any) -> str:
    """``module.name`` of the deepest module of the package holding ``obj`` under ``name``."""
    import sys

    holders = [
        m
        for m, module in list(sys.modules.items())
        if m.startswith("quadric_contact.") and getattr(module, name, None) is obj
    ]
    return max(holders, key=lambda m: m.count(".")) + "." + name


def public_api() -> str:
    """An autosummary table of every top-level name, grouped by the layer that defines it,
    each linked to where it is documented."""
    import quadric_contact as qc

    groups: dict[str, list[str]] = {}
    for name in qc.__all__:
        if name.startswith("__"):
            continue
        canonical = _canonical(f"quadric_contact.{name}") or f"quadric_contact.{name}"
        if canonical == f"quadric_contact.{name}":  # data (a table): where it is assigned
            canonical = _defined_in(name, getattr(qc, name))
        layer = canonical.split(".")[1]
        groups.setdefault(layer, []).append(canonical)
    titles = {
        "exact": "Exact numbers and errors",
        "model": "Quadrics",
        "theory": "The paper's decisions and their results",
        "modes": "Predicates, codes and stacks",
        "families": "Families",
        "scenes": "Scenes",
    }
    out = []
    for layer, title in titles.items():
        names = groups.pop(layer, [])
        if not names:
            continue
        out += [title, "-" * len(title), "", ".. autosummary::", ""]
        out += [f"   ~{n}" for n in names] + [""]
    assert not groups, f"top-level names from layers without a title: {groups}"
    return "\n".join(out)


def _write_if_changed(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def generate(app: Any) -> None:
    generated = DOCS / "_generated"
    _write_if_changed(generated / "errata_table.md", errata_table())
    _write_if_changed(generated / "errata_entries.md", errata_entries())
    _write_if_changed(generated / "public_api.rst", public_api())
    target = DOCS / "notebooks"
    target.mkdir(exist_ok=True)
    sources = sorted((ROOT / "notebooks").glob("*.ipynb"))
    for source in sources:
        copy = target / source.name
        if not copy.exists() or copy.read_bytes() != source.read_bytes():
            shutil.copyfile(source, copy)
    for stale in set(target.glob("*.ipynb")) - {target / s.name for s in sources}:
        stale.unlink()


def _canonical(target: str) -> str | None:
    """The documented name of the object Python finds at ``target``, if it exists: a class
    or function where it is defined (``module.qualname``), a module by its name, and other
    objects (data) as the module they were found in."""
    parts = target.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj: Any = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        owner = obj
        try:
            for name in parts[cut:]:
                owner, obj = obj, getattr(obj, name)
        except AttributeError:
            return None
        if isinstance(obj, type(importlib)):
            return obj.__name__
        module = getattr(obj, "__module__", None)
        qualname = getattr(obj, "__qualname__", None)
        if isinstance(module, str) and isinstance(qualname, str):
            return f"{module}.{qualname}"
        if isinstance(owner, type(importlib)):
            return f"{owner.__name__}.{parts[-1]}"
        if isinstance(owner, type):  # a property or another descriptor of a class
            return f"{owner.__module__}.{owner.__qualname__}.{parts[-1]}"
        return None
    return None


def _instance_attribute(name: str, documented: Any) -> str | None:
    """``Class.attr`` for an attribute set on instances (documented by a ``#:`` comment where
    it is assigned): the class, or the first base in its method resolution order, whose
    documented members include it."""
    owner_name, _, attr = name.rpartition(".")
    owner = _canonical(owner_name)
    if owner is None:
        return None
    module, _, qualname = owner.rpartition(".")
    try:
        cls = getattr(importlib.import_module(module), qualname)
    except (ImportError, AttributeError):
        return None
    for base in getattr(cls, "__mro__", ()):
        candidate = f"{base.__module__}.{base.__qualname__}.{attr}"
        if candidate in documented:
            return candidate
    return None


def _candidates(node: Any) -> list[str]:
    """Full names a reference may mean, in the order Python would look them up from where
    it is written: as given, in the current class, in the current module."""
    target = node["reftarget"].lstrip("~.")
    module = node.get("py:module") or ""
    cls = node.get("py:class") or ""
    out = [target]
    if module and cls:
        out.append(f"{module}.{cls}.{target}")
    if module:
        out.append(f"{module}.{target}")
    return out


# the kinds of documented object each role may name: a role that names the wrong kind of
# object (``:func:`` for a module) is a stale reference and stays unresolved
KINDS = {
    "func": {"function", "method", "classmethod", "staticmethod"},
    "meth": {"method", "classmethod", "staticmethod", "property", "function"},
    "attr": {"attribute", "property", "data", "method"},
    "data": {"data", "attribute"},
    "const": {"data", "attribute"},
    "class": {"class", "exception"},
    "exc": {"exception", "class"},
    "mod": {"module"},
    "obj": {
        "function",
        "method",
        "classmethod",
        "staticmethod",
        "property",
        "attribute",
        "data",
        "class",
        "exception",
        "module",
    },
}


def resolve_reexport(app: Any, env: Any, node: Any, contnode: Any) -> Any:
    """Resolve a reference as Python resolves the name, to where the object is documented.

    * A name imported into a module (``SmallnessCode`` in ``quadric_contact.modes.predicates``)
      or re-exported by a package (``quadric_contact.Quadric``) is the object defined
      elsewhere, documented there.
    * A name imported for type checking only is found by its unique documented full name.
    * Module-level data and private helpers, which have no entry of their own, link to the
      module that holds them.

    A name that Python does not find, or that is not of the kind its role says (a module
    named by ``:func:``), stays unresolved and fails the build (``nitpicky``)."""
    if node.get("refdomain") != "py":
        return None
    domain = env.get_domain("py")
    role = node["reftype"]
    target = node["reftarget"].lstrip("~.")

    def link(found: str) -> Any:
        entry = domain.objects.get(found)
        if entry is None or entry.objtype not in KINDS.get(role, set()):
            return None
        new = node.deepcopy()
        new["reftarget"] = found
        new["refspecific"] = False
        return domain.resolve_xref(env, node["refdoc"], app.builder, "obj", found, new, contnode)

    def holder_of(canonical: str) -> Any:
        holder, _, name = canonical.rpartition(".")
        kind_ok = role in ("data", "const", "attr", "obj") or name.startswith("_")
        if kind_ok and holder in domain.modules and canonical not in domain.objects:
            new = node.deepcopy()
            new["reftarget"] = holder
            return domain.resolve_xref(env, node["refdoc"], app.builder, "mod", holder, new, contnode)
        return None

    for name in _candidates(node):
        if not name.startswith("quadric_contact"):
            continue
        canonical = _canonical(name) or _instance_attribute(name, domain.objects)
        if canonical is None:
            continue
        ref = link(canonical) or holder_of(canonical)
        if ref is not None:
            return ref
    # names imported for type checking only: the first part by its unique documented name
    head, _, rest = target.partition(".")
    kinds = KINDS["class"] if rest else KINDS.get(role, set())
    unique = [
        n
        for n, entry in domain.objects.items()
        if n.startswith("quadric_contact") and n.endswith("." + head) and entry.objtype in kinds
    ]
    if len(unique) == 1:
        full = unique[0] + ("." + rest if rest else "")
        canonical = _canonical(full) or _instance_attribute(full, domain.objects)
        if canonical is not None:
            return link(canonical)
    return None


class CheckReferenceKinds(SphinxPostTransform):
    """Fail a reference whose role names the wrong kind of object: Sphinx resolves an exact
    name whatever its kind, so ``:func:`quadric_contact.theory.overlap``` would link to the
    module of that name although the function meant is ``quadric_contact.overlap``."""

    default_priority = 5  # before the references are resolved (10)

    def run(self, **kwargs: Any) -> None:
        env = self.env
        domain = env.get_domain("py")
        for node in self.document.findall(addnodes.pending_xref):
            role = node.get("reftype")
            if node.get("refdomain") != "py" or role not in KINDS or role == "obj":
                continue
            target = node["reftarget"].lstrip("~.")
            if not target.startswith("quadric_contact"):
                continue
            entry = domain.objects.get(target)
            if entry is not None and entry.objtype not in KINDS[role]:
                logger.warning(
                    "py:%s reference %s names a %s",
                    role,
                    target,
                    entry.objtype,
                    location=node,
                    type="ref",
                    subtype="kind",
                )


def skip_type_aliases(app: Any, what: str, name: str, obj: Any, skip: bool, options: Any) -> bool | None:
    """Type aliases (``Box = tuple[...]``) are annotations, not API: autodoc cannot format
    them as classes."""
    alias = typing.get_origin(obj) is not None and not isinstance(obj, type)
    if alias or isinstance(obj, typing.TypeVar | types.UnionType):
        return True
    return None


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", generate)
    app.connect("missing-reference", resolve_reexport)
    app.connect("autodoc-skip-member", skip_type_aliases)
    app.add_post_transform(CheckReferenceKinds)
    return {"parallel_read_safe": True, "parallel_write_safe": True}


__all__ = ["errata_entries", "errata_table", "public_api", "setup"]
