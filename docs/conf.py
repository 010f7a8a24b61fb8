"""Sphinx configuration of the vdw_frames documentation.

Build (warnings as errors, as CI does): ``python -m sphinx -W -b html docs docs/_build/html``.
The API pages are autodoc of the installed package (``pip install -e ".[docs]"``); the docstrings are
prose with Sphinx roles and, where they have sections, numpy-style sections, read by napoleon
(``_read_docstring`` below).
"""

from __future__ import annotations

import re

import vdw_frames

project = "vdw_frames"
author = "The vdw_frames developers"
copyright = "The vdw_frames developers (MIT licence)"
release = vdw_frames.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
]

exclude_patterns = ["_build"]
root_doc = "index"
language = "en"
today_fmt = "%Y-%m-%d"


autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_default_options: dict[str, bool] = {}
# Tables of names only (no stub pages): every object is documented once, on its package's page.
autosummary_generate = False

html_theme = "alabaster"
html_title = f"vdw_frames {release}"
html_theme_options = {"description": "FDMK viscoelastic damping walls in shear buildings",
                      "fixed_sidebar": True, "page_width": "1100px", "sidebar_width": "240px"}
html_static_path: list[str] = []


# The docstrings write absolute values and norms as plain text, |s| and ||x||; this project defines no
# substitutions, so every | outside literals is a character (escaped here rather than in ~50 docstrings,
# where help() would show the backslashes).
_LITERAL = re.compile(r"(``.+?``|`[^`]*`)")


def _escape_bars(line: str) -> str:
    parts = _LITERAL.split(line)
    return "".join(part if k % 2 else part.replace("|", "\\|") for k, part in enumerate(parts))


def _numpy_sections(app, what: str, name: str, obj, options, lines: list[str]) -> list[str]:
    """The numpy-style sections (Parameters, Notes, ...) of a function's, class's or module's docstring as
    reST, by napoleon's NumpyDocstring.  Not for attributes and properties: napoleon reads their first line
    "X: Y" as the type X, and these docstrings are prose ("(lowest, highest) node amplitude, dimensionless: ...")."""
    if what in ("attribute", "property", "data"):
        return lines
    from sphinx.ext.napoleon import Config
    from sphinx.ext.napoleon.docstring import NumpyDocstring

    config = Config(napoleon_google_docstring=False, napoleon_use_rtype=False)
    return NumpyDocstring(lines, config, app, what, name, obj, options).lines()


def _attribute_docs() -> dict[str, list[tuple[object, list[str]]]]:
    """Every module-level docstring of a constant in the package (``NAME = ...`` then a string), by name,
    with the value it documents."""
    import importlib
    import pkgutil

    from sphinx.pycode import ModuleAnalyzer

    docs: dict[str, list[tuple[object, list[str]]]] = {}
    for module in pkgutil.walk_packages(vdw_frames.__path__, "vdw_frames."):
        loaded = importlib.import_module(module.name)
        for (scope, attribute), doc in ModuleAnalyzer.for_module(module.name).find_attr_docs().items():
            if not scope and hasattr(loaded, attribute):
                docs.setdefault(attribute, []).append((getattr(loaded, attribute), list(doc)))
    return docs


_ATTRIBUTE_DOCS: dict[str, list[tuple[object, list[str]]]] = {}


def _data_doc(name: str, obj: object) -> list[str]:
    """A constant re-exported by a package (``vdw_frames.G``) has no docstring where autodoc looks, which
    then shows its type's (float's, dict's, ndarray's): take the docstring where it is defined, or none."""
    if not _ATTRIBUTE_DOCS:
        _ATTRIBUTE_DOCS.update(_attribute_docs())
    for value, doc in _ATTRIBUTE_DOCS.get(name.rsplit(".", 1)[-1], []):
        if value is obj:
            return doc
    return []


def _read_docstring(app, what, name, obj, options, lines: list[str]) -> None:
    """autodoc-process-docstring: numpy sections, then the bars of |x| escaped outside inline literals and
    literal blocks."""
    if what == "data":
        lines[:] = _data_doc(name, obj)
    lines[:] = _numpy_sections(app, what, name, obj, options, lines)
    block_indent = None  # the indent of the paragraph that opened a literal block (::), while inside it
    for k, line in enumerate(lines):
        indent = len(line) - len(line.lstrip())
        if block_indent is not None:
            if not line.strip() or indent > block_indent:
                continue
            block_indent = None
        lines[k] = _escape_bars(line)
        if line.rstrip().endswith("::"):
            block_indent = indent


def _python_object(name: str) -> object:
    """The package's object that a dotted name means (module, class, function, method), or None."""
    import importlib

    parts = name.split(".")
    for split in range(len(parts), 0, -1):
        try:
            value: object = importlib.import_module(".".join(parts[:split]))
        except ImportError:
            continue
        try:
            for part in parts[split:]:
                value = getattr(value, part)
        except AttributeError:
            return None
        return value
    return None


_DOCUMENTED: dict[int, tuple[object, str, str, str]] = {}


def _same_object(app, env, node, contnode):
    """missing-reference: a docstring's reference to a name by another of its paths (``vdw_frames.frame.
    simulation.simulate``, ``simulate`` inside that module, ``~vdw_frames.element.damper.FDMKDamper``) links to
    where that same object is documented (``vdw_frames.simulate``).  Nothing else changes: names the pages
    do not document stay plain text."""
    from sphinx.util.nodes import make_refnode

    if node.get("refdomain") != "py" or not str(node.get("reftarget", "")):
        return None
    domain = env.get_domain("py")
    if not _DOCUMENTED:
        for documented, entry in domain.objects.items():
            if entry.objtype in ("class", "function", "method", "property", "module", "exception"):
                value = _python_object(documented)
                if value is not None:
                    _DOCUMENTED.setdefault(id(value), (value, entry.docname, entry.node_id, documented))
    target = str(node["reftarget"]).lstrip(".~")
    context = [node.get("py:module"), node.get("py:class") and f"{node.get('py:module')}.{node.get('py:class')}"]
    for name in [target] + [f"{prefix}.{target}" for prefix in context if prefix]:
        if not name.startswith("vdw_frames"):
            continue
        value = _python_object(name)
        found = _DOCUMENTED.get(id(value)) if value is not None else None
        if found is not None and found[0] is value:
            return make_refnode(app.builder, node["refdoc"], found[1], found[2], contnode, found[3])
    return None


def _command_help() -> list[tuple[str, str]]:
    """The help of ``vdw-frames`` and of each of its commands, from the parser itself (never stale)."""
    import argparse

    from vdw_frames.cli import build_parser

    parser = build_parser()
    helps = [("vdw-frames", parser.format_help())]
    for action in parser._actions:  # argparse keeps its sub-commands in a sub-parsers action
        if isinstance(action, argparse._SubParsersAction):
            helps += [(f"vdw-frames {name}", command.format_help()) for name, command in action.choices.items()]
    return helps


def setup(app):
    from docutils import nodes
    from sphinx.util.docutils import SphinxDirective

    class CommandHelp(SphinxDirective):
        """``.. vdw-frames-help::``: a titled literal block per command."""

        def run(self):
            result = []
            for title, text in _command_help():
                section = nodes.rubric(text=title)
                block = nodes.literal_block(text, text)
                block["language"] = "text"
                result += [section, block]
            return result

    app.add_directive("vdw-frames-help", CommandHelp)
    app.connect("autodoc-process-docstring", _read_docstring)
    app.connect("missing-reference", _same_object)
    return {"parallel_read_safe": True}
