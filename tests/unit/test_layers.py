"""The layers import one way (docs/architecture.md): every import of every module, at module level and inside
functions, goes to a lower layer or within its own package, and the module graph has no cycle."""

import ast
import subprocess
import sys
from pathlib import Path

from helpers import ROOT

# lowest first; a module's layer is that of the longest prefix that names it
LAYERS = [
    ("core", ["pdverify.core"]),
    ("numerics", ["pdverify.numerics"]),
    ("theory", ["pdverify.theory"]),
    ("models", ["pdverify.papers", "pdverify.exact", "reference_fem"]),
    ("registry", ["pdverify.registry"]),
    ("measure", ["pdverify.measure"]),
    ("study", ["pdverify.study"]),
    ("verify", ["pdverify.verify"]),
    ("report", ["pdverify.report"]),
    ("apps", ["pdverify.apps", "pdverify.testing", "pdverify.__main__", "pdverify"]),
]
# within the models layer each of these is a world of its own: a paper's model never reads an exact solution's
# code nor another paper's, and a reference never reads a model's
SILOS = [
    "pdverify.papers.diyaroglu",
    "pdverify.papers.moyer",
    "pdverify.papers.yang",
    "pdverify.papers.ogrady",
    "pdverify.papers.curved",
    "pdverify.exact",
    "reference_fem",
]


def modules() -> dict[str, Path]:
    out = {}
    for top in ("pdverify", "reference_fem"):
        for p in (ROOT / top).rglob("*.py"):
            parts = list(p.relative_to(ROOT).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            out[".".join(parts)] = p
    return out


MODULES = modules()


def imports(name: str, path: Path) -> list[tuple[str, int, bool]]:
    """(imported module, line, at module level) for every import of ``path`` into pdverify or reference_fem."""
    tree = ast.parse(path.read_text())
    pkg = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = []

    def visit(node, local):
        for ch in ast.iter_child_nodes(node):
            if isinstance(ch, ast.ImportFrom):
                base = ch.module or ""
                if ch.level:
                    parts = pkg.split(".")
                    base = ".".join(parts[: len(parts) - ch.level + 1] + ([ch.module] if ch.module else []))
                for a in ch.names:
                    target = f"{base}.{a.name}" if f"{base}.{a.name}" in MODULES else base
                    found.append((target, ch.lineno, not local))
            elif isinstance(ch, ast.Import):
                found.extend((a.name, ch.lineno, not local) for a in ch.names)
            visit(ch, local or isinstance(ch, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)))

    visit(tree, False)
    return [(t, line, top) for t, line, top in found if t.split(".")[0] in ("pdverify", "reference_fem")]


def layer(name: str) -> int:
    best, rank = -1, None
    for i, (_, prefixes) in enumerate(LAYERS):
        for p in prefixes:
            if (name == p or name.startswith(p + ".")) and len(p) > best:
                best, rank = len(p), i
    return rank


def silo(name: str) -> str | None:
    return next((s for s in SILOS if name == s or name.startswith(s + ".")), None)


def test_every_module_has_a_layer():
    assert all(layer(m) is not None for m in MODULES)


def test_imports_run_down_the_layers():
    bad = []
    for name, path in MODULES.items():
        for target, line, _ in imports(name, path):
            if target not in MODULES:
                bad.append(f"{path.relative_to(ROOT)}:{line}: {target} is not a module")
                continue
            up = layer(target) > layer(name)
            across = layer(target) == layer(name) and silo(target) != silo(name)
            if (up or across) and name != "pdverify":
                bad.append(f"{path.relative_to(ROOT)}:{line}: {LAYERS[layer(name)][0]} imports {target}")
    assert not bad, "\n".join(bad)


def test_the_module_graph_has_no_cycle():
    graph = {n: {t for t, _, _ in imports(n, p) if t in MODULES and t != n} for n, p in MODULES.items()}
    graph["pdverify"] = set()  # the API's lazy imports reach down only; every module's parent package is implied
    state: dict[str, int] = {}
    cycles = []

    def walk(n, stack):
        state[n] = 1
        for t in sorted(graph[n]):
            if state.get(t) == 1:
                cycles.append(" -> ".join(stack[stack.index(t) :] + [t]))
            elif t not in state:
                walk(t, stack + [t])
        state[n] = 2

    for n in sorted(graph):
        if n not in state:
            walk(n, [n])
    assert not cycles, "\n".join(cycles)


def test_function_level_imports_say_why():
    """An import inside a function defers a heavy dependency and says so: in a comment on its line or the line
    before, or, for an entry point that defers all of them (the API, the command line), in its docstring
    ("Imports are lazy ...")."""
    bare = []
    for name, path in MODULES.items():
        text = path.read_text()
        if "Imports are lazy" in (ast.get_docstring(ast.parse(text)) or ""):
            continue
        lines = text.splitlines()
        for target, line, top in imports(name, path):
            if not top and "#" not in lines[line - 1] and "#" not in lines[line - 2]:
                bare.append(f"{path.relative_to(ROOT)}:{line}: {target}")
    assert not bare, "\n".join(bare)


def test_import_pdverify_loads_no_report_or_command_line_code():
    code = (
        "import sys, pdverify, pdverify.registry; pdverify.registry.models();"
        "print(sorted(m for m in sys.modules if m.startswith(('pdverify.report', 'pdverify.apps', 'typer', "
        "'matplotlib', 'dask'))))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True)
    assert out.stdout.strip() == "[]", out.stdout
