"""The documentation site (docs/): it builds with warnings as errors, its API pages document every public name
and module, and the getting-started guide's Python lines and commands print what the page shows."""

from __future__ import annotations

import doctest
import importlib
import pkgutil
import re
import shlex
import subprocess
import sys
import textwrap
import warnings

import pytest
from shared_data import REPO

import vdw_frames
from vdw_frames import cli

pytest.importorskip("sphinx", reason="the documentation needs Sphinx (the [docs] or [test] extra)")

DOCS = REPO / "docs"
GUIDE = DOCS / "getting-started.rst"
# Modules whose name the package gives to one of their functions (vdw_frames.verification.verify is the function).
SHADOWED_MODULES = {"vdw_frames.verification.verify"}
SUBPACKAGES = ("element", "motion", "asce7", "frame", "design", "paper", "interop", "assessment", "verification",
               "plotting")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The HTML site, built once: (output folder, Sphinx's output)."""
    out = tmp_path_factory.mktemp("html")
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html", str(DOCS), str(out)],
                         cwd=REPO, capture_output=True, text=True, timeout=600, check=False)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-5000:]
    return out, run.stdout + run.stderr


def anchors(site_dir) -> set[str]:
    """Every object and module anchor of the API pages (``id="vdw_frames..."`` and ``id="module-..."``)."""
    found: set[str] = set()
    for page in (site_dir / "api").glob("*.html"):
        found |= set(re.findall(r'id="((?:module-)?vdw_frames[\w.]*)"', page.read_text(encoding="utf-8")))
    return found


def test_the_site_builds_with_warnings_as_errors(site):
    out, log = site
    assert "build succeeded" in log
    for page in ("index", "getting-started", "theory", "validation", "changelog", "api/index", "api/toplevel"):
        assert (out / f"{page}.html").stat().st_size > 2_000, page


def test_the_api_documents_simulate_and_the_wall_at_the_top_level(site):
    out, _ = site
    toplevel = (out / "api" / "toplevel.html").read_text(encoding="utf-8")
    for name in ("vdw_frames.simulate", "vdw_frames.FDMKDamper", "vdw_frames.FDMKDamper.force",
                 "vdw_frames.FDMKDamper.storage_stiffness", "vdw_frames.ShearBuilding"):
        assert f'id="{name}"' in toplevel, name
    assert "Integrate" in toplevel  # simulate's docstring, not only its name


def test_references_by_another_path_link_to_where_the_object_is_documented(site):
    # vdw_frames.frame's docstring says :func:`simulate` (vdw_frames.frame.simulate), documented as
    # vdw_frames.simulate; vdw_frames.element's says :class:`FDMKDamper`, documented at the top level.
    out, _ = site
    assert 'href="toplevel.html#vdw_frames.simulate"' in (out / "api" / "frame.html").read_text(encoding="utf-8")
    assert 'href="toplevel.html#vdw_frames.FDMKDamper"' in (out / "api" / "element.html").read_text(encoding="utf-8")


def test_every_public_name_and_module_has_its_entry(site):
    # A name added to an __all__ (or a module added to a sub-package) without its place in docs/api fails here.
    documented = anchors(site[0])
    missing = [f"vdw_frames.{name}" for name in vdw_frames.__all__
               if f"vdw_frames.{name}" not in documented and f"module-vdw_frames.{name}" not in documented]
    for sub in SUBPACKAGES:
        package = importlib.import_module(f"vdw_frames.{sub}")
        for name in getattr(package, "__all__", ()):
            top_level = name in vdw_frames.__all__ and getattr(vdw_frames, name) is getattr(package, name)
            if f"vdw_frames.{sub}.{name}" not in documented and not (top_level and f"vdw_frames.{name}" in documented):
                missing.append(f"vdw_frames.{sub}.{name}")
        page = (site[0] / "api" / f"{sub}.html").read_text(encoding="utf-8")
        for module in pkgutil.iter_modules(package.__path__):
            name = f"vdw_frames.{sub}.{module.name}"
            if module.name.startswith("_") or f"module-{name}" in documented:
                continue
            # a module that shares its name with its package's function is documented under its heading alone
            if not (name in SHADOWED_MODULES and f'<span class="pre">{name}</span>' in page):
                missing.append(f"module {name}")
    for name in ("config", "cli"):
        if f"module-vdw_frames.{name}" not in documented:
            missing.append(f"module vdw_frames.{name}")
    assert not missing, missing


def test_the_command_line_page_shows_every_command_help(site):
    page = (site[0] / "api" / "cli.html").read_text(encoding="utf-8")
    for command in ("sine-test", "simulate", "design", "collapse", "verify", "design-building", "paper-report"):
        assert f"usage: vdw-frames {command}" in page, command


def test_the_guide_python_lines_print_what_the_page_shows(monkeypatch):
    monkeypatch.chdir(REPO)  # the guide's paths start at the repository root
    result = doctest.testfile(str(GUIDE), module_relative=False, optionflags=doctest.NORMALIZE_WHITESPACE,
                              verbose=False, report=True)
    assert result.attempted >= 10
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples of {GUIDE} failed (printed above)"


CONSOLE = re.findall(r"^\.\. code-block:: console\n\n((?:   .*\n|\n)+)", GUIDE.read_text(encoding="utf-8"), flags=re.M)


def test_the_guide_has_commands():
    assert len(CONSOLE) >= 2


@pytest.mark.parametrize("block", CONSOLE, ids=[f"command{k + 1}" for k in range(len(CONSOLE))])
def test_the_guide_commands_print_what_the_page_shows(block, tmp_path, monkeypatch, capsys):
    command, *shown = textwrap.dedent(block).strip("\n").splitlines()
    assert command.startswith("$ vdw-frames ")
    # Run where the page's relative paths resolve but the outputs (./out) land in tmp_path.
    for name in ("docs", "vdw_frames"):
        (tmp_path / name).symlink_to(REPO / name, target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("always")  # every warning printed: the page says these runs print none
        status = cli.main(shlex.split(command)[2:])
    printed = capsys.readouterr()
    assert status == 0
    assert printed.err == ""
    assert [line.rstrip() for line in printed.out.strip("\n").splitlines()] == [line.rstrip() for line in shown]


PYTHON = [(path, block) for path in sorted(DOCS.rglob("*.rst"))
          for block in re.findall(r"^\.\. code-block:: python\n\n((?:   .*\n|\n)+)", path.read_text(encoding="utf-8"),
                                  flags=re.M)]


@pytest.mark.parametrize("path, block", PYTHON, ids=[f"{path.stem}{k + 1}" for k, (path, _) in enumerate(PYTHON)])
def test_the_python_blocks_of_the_pages_run(path, block, monkeypatch):
    monkeypatch.chdir(REPO)
    namespace = {"__name__": "docs"}
    exec(compile(textwrap.dedent(block), f"{path}:python block", "exec"), namespace)
    assert namespace.keys() - {"__name__", "__builtins__"}
