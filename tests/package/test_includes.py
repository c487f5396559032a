# SPDX-License-Identifier: BSD-2-Clause
"""The FMUs' C layers (docs/architecture.md) include only downwards: fmi/ (the FMI layer) over
models/ (model.h, model_common.c and one folder a model) over rod/ over contact/ over common/. A
model's files include their own folder's and models/'s, never another model's; no header includes
itself back through others. Read from the sources' #include lines; a name found nowhere in fmu_src/
(the C library, SUNDIALS, the FMI headers, what the build generates) is outside the layers."""
import re

from conftest import ROOT

FMU_SRC = ROOT / "fmu_src"
RANK = {"fmi": 0, "models": 1, "rod": 2, "contact": 3, "common": 4}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)


def layer(path, src):
    return path.relative_to(src).parts[0]


def model_of(path, src):
    """NAME for a file of models/NAME/, None for any other."""
    parts = path.relative_to(src).parts
    return parts[1] if parts[0] == "models" and len(parts) > 2 else None


def sources(src):
    return sorted(p for p in src.rglob("*") if p.suffix in (".c", ".h"))


def resolve(name, includer, src, files):
    """The files of fmu_src/ that `#include name` in `includer` may mean: the includer's own
    folder first, and config.h is the model's own (from model.h: any model's)."""
    own = includer.parent / name
    if own.exists():
        return [own]
    found = [f for f in files if f.name == name]
    if name == "config.h" and model_of(includer, src):
        found = [f for f in found if model_of(f, src) == model_of(includer, src)]
    return found


def upward_includes(src):
    """'includer -> included' for every include that runs up a layer or into another model."""
    files = sources(src)
    wrong = []
    for f in files:
        for name in INCLUDE.findall(f.read_text()):
            for g in resolve(name, f, src, files):
                up = RANK[layer(g, src)] < RANK[layer(f, src)]
                other_model = model_of(g, src) not in (None, model_of(f, src)) and not (
                    g.name == "config.h" and model_of(f, src) is None)
                if up or other_model:
                    wrong.append(f"{f.relative_to(src)} -> {g.relative_to(src)}")
    return wrong


def include_circles(src):
    """The files that include themselves back through others."""
    files = sources(src)
    edges = {f: [g for name in INCLUDE.findall(f.read_text()) for g in resolve(name, f, src, files)] for f in files}
    circles, done = [], set()

    def visit(f, path):
        if f in path:
            circles.append(" -> ".join(str(p.relative_to(src)) for p in path[path.index(f):] + [f]))
            return
        if f in done:
            return
        for g in edges[f]:
            visit(g, path + [f])
        done.add(f)

    for f in files:
        visit(f, [])
    return circles


def test_every_include_runs_down_the_layers():
    assert set(p.name for p in FMU_SRC.iterdir() if p.is_dir()) == set(RANK)
    assert upward_includes(FMU_SRC) == []


def test_no_include_circles():
    assert include_circles(FMU_SRC) == []


def test_the_checks_find_an_upward_include_another_models_file_and_a_circle(tmp_path):
    """The checks can fail: on a small tree with each fault, each is reported."""
    for folder, name, text in [
            ("fmi", "instance.h", '#include "model.h"\n'),
            ("models", "model.h", "#include <config.h>\n"),
            ("models/A", "config.h", '#include "rod.h"\n'),
            ("models/A", "a.c", '#include "model.h"\n#include "b.h"\n'),
            ("models/B", "config.h", ""),
            ("models/B", "b.h", ""),
            ("rod", "rod.h", '#include "contact.h"\n'),
            ("contact", "contact.h", '#include "namespace.h"\n#include "instance.h"\n'),
            ("common", "namespace.h", "")]:
        (tmp_path / folder).mkdir(parents=True, exist_ok=True)
        (tmp_path / folder / name).write_text(text)
    assert upward_includes(tmp_path) == ["contact/contact.h -> fmi/instance.h", "models/A/a.c -> models/B/b.h"]
    assert include_circles(tmp_path) == [
        "contact/contact.h -> fmi/instance.h -> models/model.h -> models/A/config.h -> rod/rod.h -> contact/contact.h"]
