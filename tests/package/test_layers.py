# SPDX-License-Identifier: BSD-2-Clause
"""The harness's layers (docs/architecture.md) import only downwards: theory < experiments < fmu <
coupling, validation, sweep < figures < cli; no module imports itself back through others; the
theory and the experiments load no fmpy; nothing imports the CLI; the top level is the public
face alone. Read from the sources' import statements (those inside functions too)."""
import ast
import pathlib

import pytest

from conftest import ROOT

PACKAGE = ROOT / "python_harness" / "painleve"
RANK = {"theory": 0, "experiments": 1, "fmu": 2, "coupling": 3, "validation": 3, "sweep": 3, "figures": 4, "cli": 5}


def module_name(path):
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports_of(path):
    """The absolute names that `path` imports: `from .x import y` as painleve.<...>.x(.y)."""
    here = module_name(path)
    package = here if path.name == "__init__.py" else here.rsplit(".", 1)[0]
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[:len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([node.module] if node.module else []))
            names |= {base} | {f"{base}.{a.name}" for a in node.names}
    return names


MODULES = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}
INTERNAL = {m: {i for i in imports_of(p) if i in MODULES and i != m and i != "painleve"} for m, p in MODULES.items()}


def layer(module):
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else None


def test_the_top_level_holds_the_public_face_alone():
    assert sorted(p.name for p in PACKAGE.glob("*.py")) == ["__init__.py", "__main__.py"]
    assert {p.name for p in PACKAGE.iterdir() if p.is_dir() and p.name != "__pycache__"} == set(RANK)


@pytest.mark.parametrize("module", sorted(m for m in MODULES if layer(m) in RANK))
def test_a_module_imports_its_own_layer_or_the_layers_below(module):
    upward = [i for i in INTERNAL[module] if layer(i) in RANK and layer(i) != layer(module)
              and RANK[layer(i)] >= RANK[layer(module)]]
    assert not upward, f"{module} imports {upward}: a layer imports only the layers below it"


@pytest.mark.parametrize("module", sorted(m for m in MODULES if layer(m) in ("theory", "experiments")))
def test_the_theory_and_the_experiments_load_no_fmpy(module):
    fmpy = [i for i in imports_of(MODULES[module]) if i == "fmpy" or i.startswith("fmpy.")]
    assert not fmpy, f"{module} imports {fmpy}"


def test_no_module_reaches_itself_through_its_imports():
    def reaches(start):
        seen, todo = set(), [start]
        while todo:
            for i in INTERNAL[todo.pop()]:
                if i not in seen:
                    seen.add(i)
                    todo.append(i)
        return seen
    circles = sorted(m for m in MODULES if m in reaches(m) and not m.endswith("__init__"))
    assert not circles, f"modules on a circle of imports: {circles}"


def test_importing_the_package_and_its_theory_loads_no_fmpy():
    import subprocess
    import sys
    code = ("import sys, painleve, painleve.theory.analytic, painleve.experiments.reference; "
            "from painleve import analytic, rigid_limit, Case; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'fmpy'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
