"""The guides point at what exists and read as guides: every relative link and every repository path or
``pdverify.<module>`` name in README.md, tests/README.md and docs/**/*.md exists; no dates and no issue numbers
(git keeps the history)."""

import re

import pytest
from helpers import ROOT

DOCS = sorted(
    [ROOT / "README.md", ROOT / "tests" / "README.md", *(ROOT / "docs").rglob("*.md")],
    key=lambda p: str(p),
)
IDS = [str(p.relative_to(ROOT)) for p in DOCS]

# [text](target) and <img src="target">, not http(s) or mailto; the #fragment is dropped
LINK = re.compile(r"\]\(([^)\s]+)\)|src=\"([^\"]+)\"")
# a path from the repository's root: tests/..., pdverify/..., reference_fem/..., studies/..., docs/..., examples/...
PATH = re.compile(r"(?<![\w/.\-])((?:tests|pdverify|reference_fem|studies|docs|examples|benchmarks)/[\w./\-<>]*)")
# a placeholder in a path: studies/paper_yang/SCENE.toml, reports/verify/<model>
PLACEHOLDER = re.compile(r"(^|/)[A-Z][A-Z_]+(\.\w+)?$|<")
# a dotted module name: pdverify.study.runner, pdverify.numerics.linalg.solve_linear
MODULE = re.compile(r"(?<![\w/.])(pdverify(?:\.\w+)+)")
NOT_MODULES = {"pdverify.models"}  # the plug-ins' entry-point group
DATE = re.compile(r"\b(?:19|20)\d\d-[01]\d-[0-3]\d\b")
ISSUE = re.compile(r"\bissues?\s*#?\d+|(?<![\w&])#\d+\b", re.IGNORECASE)


def _text(doc):
    return doc.read_text(encoding="utf-8")


@pytest.mark.parametrize("doc", DOCS, ids=IDS)
def test_relative_links_exist(doc):
    missing = []
    for m in LINK.finditer(_text(doc)):
        target = (m.group(1) or m.group(2)).split("#")[0]
        if not target or re.match(r"[a-z]+:", target):
            continue
        if not (doc.parent / target).exists():
            missing.append(target)
    assert not missing, f"{doc.relative_to(ROOT)} links to missing files: {missing}"


@pytest.mark.parametrize("doc", DOCS, ids=IDS)
def test_repository_paths_exist(doc):
    missing = []
    for m in PATH.finditer(_text(doc)):
        path = m.group(1).rstrip(".-")
        if not (ROOT / path).exists() and not PLACEHOLDER.search(path):
            missing.append(path)
    assert not missing, f"{doc.relative_to(ROOT)} names paths that do not exist: {sorted(set(missing))}"


def _module_name_exists(name: str) -> bool:
    """``pdverify.a.b[.attr]``: the longest prefix is a module or package, and what follows it (one name) is defined
    or imported in that module's source."""
    parts = name.split(".")
    for k in range(len(parts), 0, -1):
        base = ROOT.joinpath(*parts[:k])
        src = base / "__init__.py" if base.is_dir() else base.with_suffix(".py")
        if src.exists():
            rest = parts[k:]
            if not rest:
                return True
            if len(rest) > 1 and not (base.is_dir() and (base / rest[0]).exists()):
                return False
            return re.search(rf"\b{re.escape(rest[0])}\b", src.read_text(encoding="utf-8")) is not None
    return False


@pytest.mark.parametrize("doc", DOCS, ids=IDS)
def test_module_names_exist(doc):
    missing = {m.group(1).rstrip(".") for m in MODULE.finditer(_text(doc))}
    missing = sorted(n for n in missing - NOT_MODULES if not _module_name_exists(n))
    assert not missing, f"{doc.relative_to(ROOT)} names modules or functions that do not exist: {missing}"


@pytest.mark.parametrize("doc", DOCS, ids=IDS)
def test_no_dates_or_issue_numbers(doc):
    text = _text(doc)
    found = [m.group(0) for m in DATE.finditer(text)] + [m.group(0) for m in ISSUE.finditer(text)]
    assert not found, f"{doc.relative_to(ROOT)} holds history (dates, issue numbers): {found[:10]}"


def test_the_contracts_table_of_variant_rules_lists_every_rule():
    """docs/contract.md's table of variant rules names each (model, variant, option) a model's ``variant_rules``
    holds: a rule the code checks is one the guide tells."""
    from pdverify.registry import models

    rows = [
        [c.strip() for c in line.strip().strip("|").split("|")]
        for line in (ROOT / "docs" / "contract.md").read_text(encoding="utf-8").splitlines()
        if line.startswith("| pd-")
    ]
    missing = []
    for name, model in models().items():
        for rule in getattr(model, "variant_rules", ()):
            variant = dict(rule.when).get("variant")
            if not any(
                name in row[0].split(", ")
                and (variant is None or variant in row[1])
                and rule.option in [o.strip() for o in row[2].split("/")]
                for row in rows
                if len(row) == 5
            ):
                missing.append((name, variant, rule.option))
    assert not missing, f"docs/contract.md's variant-rule table lacks {missing}"
