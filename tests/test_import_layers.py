"""The packages' floors (docs/architecture.md): every import points down, none runs in
a circle, and planning_core holds no command-line code. An import is an ``import``
statement anywhere in a module (a lazy one inside a function too) or a string that
names one of the project's modules (what importlib would import by name)."""

from __future__ import annotations

import ast
from functools import lru_cache

import pytest

from tests.conftest import ROOT

FLOORS = {"planning_core": 0, "cli_common": 1, "rrt_cli": 2, "validator": 2, "grading": 3,
          "benchmarks": 4, "rrt_startup": 5}
"""A package imports only packages on lower floors (rrt_cli and validator side by side;
rrt_startup, what the launchers run first, names the compiled modules of every floor).
A package's ``__main__`` (a process's entry, which nothing imports) may import
rrt_startup to set the process up."""


def _module_name(path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@lru_cache(maxsize=1)
def modules() -> dict:
    return {_module_name(path): path for package in FLOORS
            for path in (ROOT / package).rglob("*.py")}


def _project_module(name: str) -> str | None:
    """The project module ``name`` is, or is inside (``a.b.C`` -> ``a.b``); None outside."""
    known = modules()
    while name and name not in known:
        name = name.rpartition(".")[0]
    return name or None


def _imported(module: str, node: ast.AST) -> list[str]:
    if isinstance(node, ast.Import):
        return [alias.name for alias in node.names]
    if not isinstance(node, ast.ImportFrom):
        return []
    base = node.module or ""
    if node.level:
        package = module if modules()[module].name == "__init__.py" else module.rpartition(".")[0]
        for _ in range(node.level - 1):
            package = package.rpartition(".")[0]
        base = f"{package}.{base}" if base else package
    return [f"{base}.{alias.name}" for alias in node.names]


@lru_cache(maxsize=1)
def edges() -> dict[str, set[tuple[str, bool]]]:
    """module -> {(imported project module, by name)}."""
    graph: dict[str, set[tuple[str, bool]]] = {}
    for module, path in modules().items():
        found = graph.setdefault(module, set())
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Constant) and node.value in modules():
                found.add((node.value, True))
            for name in _imported(module, node):
                target = _project_module(name)
                if target is not None and target != module:
                    found.add((target, False))
    return graph


def _upward(package: str, by_name: bool) -> list[str]:
    return [f"{module} -> {target}" for module, targets in sorted(edges().items())
            if module.split(".")[0] == package and not module.endswith(".__main__")
            for target, named in sorted(targets) if named == by_name
            and target.split(".")[0] != package
            and FLOORS[target.split(".")[0]] >= FLOORS[package]]


@pytest.mark.parametrize("package", sorted(FLOORS))
def test_import_statements_point_down(package):
    assert _upward(package, by_name=False) == []


@pytest.mark.parametrize("package", sorted(FLOORS))
def test_modules_named_by_string_point_down(package):
    assert _upward(package, by_name=True) == []


def circles(package: str) -> list[list[str]]:
    """The strongly connected components (more than one module) of ``package``'s graph."""
    graph = {module: sorted(target for target, _ in targets if target.split(".")[0] == package)
             for module, targets in edges().items() if module.split(".")[0] == package}
    order: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found: list[list[str]] = []

    def visit(module: str) -> None:
        order[module] = low[module] = len(order)
        stack.append(module)
        for target in graph[module]:
            if target not in order:
                visit(target)
                low[module] = min(low[module], low[target])
            elif target in stack:
                low[module] = min(low[module], order[target])
        if low[module] == order[module]:
            component = stack[stack.index(module):]
            del stack[stack.index(module):]
            if len(component) > 1:
                found.append(sorted(component))

    for module in sorted(graph):
        if module not in order:
            visit(module)
    return found


@pytest.mark.parametrize("package", sorted(FLOORS))
def test_no_circles(package):
    assert circles(package) == []


RENDER_FLOORS = {"render_file": 0, "render_geometry": 0, "render_page": 1, "render_scene": 1,
                 "render_html": 1, "render_svg": 1, "render_plot": 2, "render_grid": 2,
                 "render_kinodynamic": 3, "render_geometric": 3, "render_pdf": 4,
                 "render_png": 5, "render_output": 6}
"""The pictures' modules by floor: what every picture draws (render_geometry) and the
atomic write (render_file) at the bottom; the PDF's page, the view's scene and its HTML
and SVG writers over them; the PDF's frames, its grid page, its family pages, its entry
(render_pdf), the PNG from it; render_output, which picks one by -o's extension, on top."""
WITHOUT_REPORTLAB = ("render_file", "render_geometry", "render_scene", "render_html",
                     "render_svg", "render_output")


def test_the_render_modules_import_one_way():
    render = {module.rpartition(".")[2]: {target.rpartition(".")[2] for target, _ in targets
                                          if ".render_" in target}
              for module, targets in edges().items() if module.startswith("validator.render_")}
    assert set(render) == set(RENDER_FLOORS)
    upward = [f"{module} -> {target}" for module, targets in render.items() for target in targets
              if RENDER_FLOORS[target] >= RENDER_FLOORS[module]]
    assert upward == []


def test_the_view_the_svg_and_the_geometry_import_no_reportlab():
    """-o FILE.html and .svg need nothing beyond the standard library."""
    for name in WITHOUT_REPORTLAB:
        tree = ast.parse((ROOT / "validator" / f"{name}.py").read_text())
        imported = [n for node in ast.walk(tree) for n in _imported(f"validator.{name}", node)]
        assert not [n for n in imported if n.split(".")[0] in ("reportlab", "pypdfium2")], name
        below = {target for target, _ in edges()[f"validator.{name}"] if ".render_" in target}
        allowed = {f"validator.{m}" for m in WITHOUT_REPORTLAB}
        if name == "render_output":  # imports the PDF's and PNG's writers only to draw them
            allowed |= {"validator.render_pdf", "validator.render_png"}
        assert below <= allowed, name


def test_planning_core_has_no_command_line_code():
    """No argument parsing and no standard stream in the core: the command lines' share
    is cli_common's."""
    offenders = []
    for module, path in modules().items():
        if module.split(".")[0] != "planning_core":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            names = _imported(module, node)
            if any(name.split(".")[0] in ("argparse", "getopt") for name in names):
                offenders.append(f"{module} imports argparse")
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                    and node.value.id == "sys" and node.attr in ("argv", "stdin", "stdout", "stderr")):
                offenders.append(f"{module} uses sys.{node.attr}")
    assert offenders == []
