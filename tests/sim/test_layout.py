# SPDX-License-Identifier: GPL-3.0-or-later
"""The engine's layout (issue 25): ``sim`` is subpackages in the order of the paper's data flow,
each importing only the ones below it that it may (the table in LAYERS), and nothing in it
imports Blender. The imports are read from the sources (ast, nothing imported), function-level
ones included."""

import ast
import subprocess
import sys

from tests.paths import ROOT

SIM = ROOT / "sim"

# layer order and what each package may import (sim/<package>/__init__.py says the same)
LAYERS = {
    "core": (),
    "image": ("core",),
    "brush": ("core",),
    "paper": ("core", "image"),
    "surface": ("core", "paper"),
    "engine": ("core", "brush", "paper", "surface"),
    "writing": ("core", "image", "brush", "paper", "engine"),
    "picture": ("core", "image", "engine", "writing"),
    "fitting": ("core", "image", "brush", "paper", "surface", "engine", "writing", "picture"),
    "cli": (
        "core",
        "image",
        "brush",
        "paper",
        "surface",
        "engine",
        "writing",
        "picture",
        "fitting",
    ),
}
TOP = ("__init__.py", "__main__.py")  # sim's own modules: they may import every package
BLENDER = {"bpy", "bpy_extras", "mathutils", "bmesh", "gpu", "blf"}
ONE_IDEA = {  # over MAX_LINES, one idea
    "brush/mark.py",  # the primitive's cut, Eq. 21-23
    "brush/dynamics.py",  # the brush step of Sec. 5.2, for many primitives as arrays and for one
    # on Python floats, the same numbers (issue 28: tests/sim/test_step_one.py holds them equal)
}
MAX_LINES = 600


def _module_name(path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path):
    """(absolute module imported, line) of every import in the file; ``from X import a`` counts
    as an import of X.a when that is a module or package of sim."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    name = _module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield a.name, node.lineno
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module
            for a in node.names:
                sub = f"{mod}.{a.name}"
                yield (sub if _is_sim_module(sub) else mod), node.lineno


def _is_sim_module(dotted: str) -> bool:
    p = ROOT.joinpath(*dotted.split("."))
    return p.with_suffix(".py").is_file() or (p / "__init__.py").is_file()


def _package_of(dotted: str) -> str | None:
    """The subpackage of sim a module belongs to; "" for sim itself; None outside sim."""
    parts = dotted.split(".")
    if parts[0] != "sim":
        return None
    return parts[1] if len(parts) > 1 and (SIM / parts[1]).is_dir() else ""


def package_graph() -> dict:
    """{package: {imported package: [where, ...]}} over every module of sim's subpackages."""
    graph = {}
    for path in sorted(SIM.rglob("*.py")):
        pkg = _package_of(_module_name(path))
        if not pkg:
            continue
        edges = graph.setdefault(pkg, {})
        for mod, line in _imports(path):
            target = _package_of(mod)
            if target is not None and target != pkg:
                edges.setdefault(target, []).append(f"{path.relative_to(ROOT)}:{line} ({mod})")
    return graph


def test_every_module_of_sim_is_in_a_package_of_the_layout():
    loose = [p.name for p in SIM.glob("*.py") if p.name not in TOP]
    assert not loose, f"modules outside the packages of the layout: {loose}"
    packages = {p.name for p in SIM.iterdir() if (p / "__init__.py").is_file()}
    assert packages == set(LAYERS), f"packages not in LAYERS (or gone): {packages ^ set(LAYERS)}"
    for pkg in LAYERS:
        doc = ast.get_docstring(ast.parse((SIM / pkg / "__init__.py").read_text("utf-8")))
        assert doc and "May import" in doc, f"sim/{pkg}/__init__.py: say what it may import"


def test_the_packages_import_only_what_their_layer_may():
    order = list(LAYERS)
    for pkg, may in LAYERS.items():  # the table itself: only packages below
        assert all(order.index(m) < order.index(pkg) for m in may), pkg
    bad = [
        f"sim.{pkg} imports {'sim itself' if not target else 'sim.' + target}: {where[0]}"
        for pkg, edges in package_graph().items()
        for target, where in edges.items()
        if target not in LAYERS[pkg]
    ]
    assert not bad, "imports against the layer order:\n" + "\n".join(bad)


def test_the_import_graph_between_packages_is_acyclic():
    graph = {pkg: set(edges) for pkg, edges in package_graph().items()}
    done, path = set(), []

    def visit(pkg):
        if pkg in path:
            raise AssertionError("import cycle: " + " -> ".join(path[path.index(pkg) :] + [pkg]))
        if pkg in done:
            return
        path.append(pkg)
        for nxt in sorted(graph.get(pkg, ())):
            visit(nxt)
        path.pop()
        done.add(pkg)

    for pkg in sorted(graph):
        visit(pkg)


def test_no_blender_import_in_sim_sources():
    bad = [
        f"{path.relative_to(ROOT)}:{line} imports {mod}"
        for path in sorted(SIM.rglob("*.py"))
        for mod, line in _imports(path)
        if mod and mod.split(".")[0] in BLENDER
    ]
    assert not bad, "\n".join(bad)


def test_sim_does_not_import_blender():
    """Every module of sim imported in a fresh interpreter: no Blender module comes in."""
    code = (
        "import importlib, pkgutil, sys, sim; "
        "[importlib.import_module(m.name) for m in pkgutil.walk_packages(sim.__path__, 'sim.')]; "
        f"bad = [m for m in {sorted(BLENDER)!r} if m in sys.modules]; "
        "print(bad); sys.exit(1 if bad else 0)"
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr


def test_modules_hold_one_idea_each():
    long = [
        f"{path.relative_to(SIM)}: {n} lines"
        for path in sorted(SIM.rglob("*.py"))
        if (n := len(path.read_text(encoding="utf-8").splitlines())) > MAX_LINES
        and path.relative_to(SIM).as_posix() not in ONE_IDEA
    ]
    assert not long, f"over {MAX_LINES} lines: split by idea, or name it in ONE_IDEA: {long}"


# ----------------------------------------------------------------------------- the Blender glue
GLUE = ROOT / "blender"
# blender/'s modules in the order they may import each other (blender/__init__.py says the same)
GLUE_ORDER = (
    "runtime",
    "checks",
    "transforms",
    "frames",
    "recordings",
    "images",
    "keyframes",
    "surfaces",
    "primitives",
    "playback",
    "materials",
    "presets",
    "scene_setup",
    "properties",
    "jobs",
    "writing",
    "work",
    "handlers",
)
ADDON_CODE = ("blender", "operators", "panels")


def _glue_imports(path):
    """The add-on modules a module of the glue imports, by their path inside the add-on."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = path.parent.relative_to(ROOT).parts[: len(path.parent.relative_to(ROOT).parts)
                                                        - node.level + 1]  # fmt: skip
            mod = list(base) + (node.module.split(".") if node.module else [])
            for a in node.names:
                yield ".".join(mod + [a.name]), node.lineno


def test_the_glue_is_one_package_whose_modules_import_only_those_before_them():
    modules = {p.stem for p in GLUE.glob("*.py")} - {"__init__"}
    assert modules == set(GLUE_ORDER), (
        f"blender/ modules not in GLUE_ORDER: {modules ^ set(GLUE_ORDER)}"
    )
    loose = {p.name for p in ROOT.glob("*.py")} - {"__init__.py"}
    assert not loose, f"Blender glue outside blender/: {loose}"
    bad = []
    for name in GLUE_ORDER:
        path = GLUE / f"{name}.py"
        for mod, line in _glue_imports(path):
            parts = mod.split(".")
            if parts[0] in ("operators", "panels"):
                bad.append(f"blender/{name}.py:{line} imports {mod} (the glue never calls up)")
            elif parts[0] == "blender" and len(parts) > 1 and parts[1] in GLUE_ORDER:
                if GLUE_ORDER.index(parts[1]) >= GLUE_ORDER.index(name):
                    bad.append(f"blender/{name}.py:{line} imports {mod}, which comes after it")
    assert not bad, "\n".join(bad)


def test_no_module_level_state_is_set_with_global_statements():
    bad = [
        f"{path.relative_to(ROOT)}:{node.lineno}"
        for folder in ADDON_CODE
        for path in sorted((ROOT / folder).rglob("*.py"))
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
        if isinstance(node, ast.Global | ast.Nonlocal)
    ]
    assert not bad, "keep runtime state in blender.runtime.Runtime: " + ", ".join(bad)
