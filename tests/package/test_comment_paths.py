# SPDX-License-Identifier: BSD-2-Clause
"""Comments describe the code as it is: every file path a comment or docstring names exists, and no
line of the code, its tests or its benchmarks carries an issue number (history belongs in docs/ and
commits).

A path is a token with a folder and an extension (`fmu_src/models/model.h`, `tests/fmu/test_body.py`), read
from Python comments and docstrings, C comments and the `#` comments of CMake and shell files. It
exists relative to the repository's root, the commenting file's folder or one of that folder's
parents (C sources name headers from fmu_src/, as the compiler finds them); a glob must match a
file. Not checked: what the build or the main job makes (build/, out/), what lives inside an FMU
archive (documentation/, binaries/, resources/, sources/, terminalsAndIcons/), the SUNDIALS tree
(sundials/) or Apple's SDK (mach-o/), and
placeholders (a part in capitals such as NAME or OUT_DIR, an elided `...`)."""
import ast
import io
import re
import tokenize

import pytest

from conftest import ROOT

SCANNED = ("fmu_src", "python_harness", "cmake", "bench", "tests")
NO_ISSUE_NUMBERS = ("fmu_src", "python_harness", "cmake", "CMakeLists.txt", "bench", "tests")
NOT_IN_THE_TREE = ("build/", "out/", "documentation/", "binaries/", "resources/", "sources/", "sundials/",
                   "terminalsAndIcons/", "mach-o/")
SKIPPED_FOLDERS = {".venv", "__pycache__", "target", ".tools"}

PATH = re.compile(r"(?<![\w./:~$-])((?:\.{1,2}/)?[\w.*-]+(?:/[\w.*-]+)+\.[A-Za-z]{1,5})(?![\w/])")
C_COMMENT_OR_STRING = re.compile(r"/\*.*?\*/|//[^\n]*|\"(?:\\.|[^\"\\\n])*\"", re.S)
ISSUE = re.compile(r"\bissues? ?#?\d|ISSUE\d+\.md", re.I)   # with or without "#" and spaces, ISSUE<N>.md


def python_comments(text):
    """(line, text) of every comment and docstring."""
    found = [(t.start[0], t.string) for t in tokenize.generate_tokens(io.StringIO(text).readline)
             if t.type == tokenize.COMMENT]
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            doc = ast.get_docstring(node, clean=False)
            if doc is not None:
                found.append((node.body[0].lineno, doc))
    return found


def c_comments(text):
    return [(text.count("\n", 0, m.start()) + 1, m.group()) for m in C_COMMENT_OR_STRING.finditer(text)
            if not m.group().startswith('"')]


def hash_comments(text):
    return [(i, line[line.index("#"):]) for i, line in enumerate(text.splitlines(), 1) if "#" in line]


def comments_of(path):
    text = path.read_text(errors="replace")
    if path.suffix == ".py":
        return python_comments(text)
    if path.suffix in (".c", ".h", ".java"):
        return c_comments(text)
    if path.suffix in (".cmake", ".sh", ".toml") or path.name in ("CMakeLists.txt", "requirements.txt"):
        return hash_comments(text)
    return []


def source_files():
    files = [ROOT / "CMakeLists.txt"]
    for folder in SCANNED:
        files += [p for p in sorted((ROOT / folder).rglob("*"))
                  if p.is_file() and not SKIPPED_FOLDERS & set(p.relative_to(ROOT).parts)]
    return files


def named_paths(comment):
    for m in PATH.finditer(comment):
        token = m.group(1)
        if token.startswith(NOT_IN_THE_TREE) or "..." in token or any(
                re.fullmatch(r"[A-Z][A-Z0-9_]+", part) for part in token.split("/")[:-1] + [token.rsplit("/", 1)[-1].split(".")[0]]):
            continue
        yield token


def exists(token, source):
    folders = [ROOT] + [f for f in source.parents if ROOT in f.parents or f == ROOT]
    for folder in folders:
        if "*" in token:
            if any(folder.glob(token)):
                return True
        elif (folder / token).exists():
            return True
    return False


def missing_paths(files):
    return [f"{path.relative_to(ROOT)}:{line}: {token}"
            for path in files for line, comment in comments_of(path)
            for token in named_paths(comment) if not exists(token, path)]


def test_every_path_a_comment_names_exists():
    assert missing_paths(source_files()) == []


def issue_numbers(files, root=ROOT):
    return [f"{p.relative_to(root)}:{i}: {line.strip()}" for p in files
            for i, line in enumerate(p.read_text(errors="replace").splitlines(), 1) if ISSUE.search(line)]


def test_no_issue_numbers_in_the_code():
    files = []
    for name in NO_ISSUE_NUMBERS:
        top = ROOT / name
        files += [top] if top.is_file() else [p for p in sorted(top.rglob("*")) if p.is_file()
                                              and not SKIPPED_FOLDERS & set(p.relative_to(ROOT).parts)]
    assert issue_numbers(files) == []


def test_the_scan_finds_issue_numbers_in_any_spelling(tmp_path):
    """The check can fail: each spelling of an issue number is reported, a plain number is not."""
    probe = tmp_path / "probe.py"
    spellings = ["# fixed in issue " + "#12", '"""See ISSUE' + '15.md."""', "x = 1  # as issue " + "23 found",
                 "/* the issue" + "23 hang */", "# Issue " + "#26: one FMU"]
    probe.write_text("\n".join(spellings + ["# 12 cases, #define N 3, tissue 4"]) + "\n")
    assert len(issue_numbers([probe], tmp_path)) == len(spellings)


@pytest.mark.parametrize("suffix, text", [
    (".py", '"""Checked by tests/fmu/test_no_such_file.py."""\nx = 1  # see fmu/no_such_module.py\n'),
    (".c", "/* the layout: fmi/no_such_header.h */\nint x; // also models/Nope/config.h\n"),
    (".cmake", "# made by cmake/no_such_script.py\nset(X 1)\n"),
])
def test_the_scan_finds_a_path_that_does_not_exist(tmp_path, suffix, text):
    """The check can fail: a comment naming files that are nowhere is reported, once per path."""
    source = ROOT / "tests" / "package" / f"_probe{suffix}"
    probe = tmp_path / f"probe{suffix}"
    probe.write_text(text)
    found = [token for _, c in comments_of(probe) for token in named_paths(c) if not exists(token, source)]
    assert len(found) == 2 - (suffix == ".cmake")


def test_the_scan_accepts_paths_relative_to_the_root_and_to_a_parent_folder():
    source = ROOT / "fmu_src" / "models" / "ShakerTable" / "config.h"
    assert exists("models/PainleveRod/config.h", source) and exists("tests/package/test_layers.py", source)
    assert exists("tests/theory/test_*.py", source)
    assert list(named_paths("see build/PainleveRod.fmu, profiles/NAME.h and src/.../X.java")) == []
