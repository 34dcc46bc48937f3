#!/usr/bin/env python3
"""Shows that check_docs.py fails when it should, so it cannot silently pass everything.

Usage: test_check_docs.py

Writes a tiny repository into a temporary folder (a README, docs/pipeline.md with a stage map,
CMakeLists.txt, a few sources), checks that check_docs.py passes on it, then breaks it one way at
a time (a missing path, a pattern that matches nothing, a missing anchor, a broken relative
link, a stage map with a wrong link, a missing stage) and checks that each fails with exit
status 1 and names the problem. Python 3 standard library only.
"""

import os
import re
import subprocess
import sys
import tempfile

CHECKER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_docs.py")

CMAKE = """\
function(inim_stage name)
endfunction()
inim_stage(core glm::glm TBB::tbb)
inim_stage(field inim_core embree)
inim_stage(runs inim_field inim_core ${SOME_LIBRARY} PkgConfig::OIIO)
"""

PIPELINE = """\
# Pipeline

## Where each step lives

| step | folder | what it holds |
|---|---|---|
| shared | `src/core/` | value types |
| field | `src/field/` | the `Field` interface (`field/field.h`) |

## Stage libraries and their links

| stage | links (inim stages) |
|---|---|
| `core` | (none) |
| `field` | `core` |
| `runs` | `field`, `core` |
"""

README = """\
# tiny

See [the pipeline](docs/pipeline.md#where-each-step-lives), `src/core/a.h`, src/field/field.h,
the commands `src/cli/cmd_<name>.cpp`, both `src/core/a.{h,cpp}` and `tests/core/*.cpp`.
Outputs are not checked: `inim eia --out out/eia.exr`, `build/release/inim`,
`inim study x --out validation/x`.
"""

FILES = {
    "CMakeLists.txt": CMAKE,
    "README.md": README,
    "docs/pipeline.md": PIPELINE,
    "docs/other.md": "# Other\n\nBack to [the README](../README.md) and [steps](pipeline.md#where-each-step-lives).\n",
    "src/core/a.h": "",
    "src/core/a.cpp": "",
    "src/field/field.h": "",
    "src/cli/cmd_eia.cpp": "",
    "tests/core/test_a.cpp": "",
}


def write_repo(root, files):
    for rel, text in files.items():
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)


def run_checker(files):
    with tempfile.TemporaryDirectory() as root:
        write_repo(root, files)
        # Not a git repository (or one that does not track it): the checker walks the tree.
        p = subprocess.run([sys.executable, CHECKER, root], capture_output=True, text=True,
                           env=dict(os.environ, GIT_CEILING_DIRECTORIES=os.path.dirname(root)))
        return p.returncode, p.stdout + p.stderr


def case(name, files, want_rc, want_lines):
    rc, out = run_checker(files)
    last = out.strip().splitlines()[-1] if out.strip() else ""
    ok = rc == want_rc and re.fullmatch(r"\d+ passed, \d+ failed", last) is not None
    for pattern in want_lines:
        if not re.search(pattern, out):
            ok = False
    if want_rc == 0 and not re.fullmatch(r"[1-9]\d* passed, 0 failed", last):
        ok = False
    print(f"{'ok  ' if ok else 'FAIL'} {name}: exit {rc}, {last}")
    if not ok:
        print("  expected exit", want_rc, "and lines matching", want_lines)
        print("  " + out.replace("\n", "\n  "))
    return ok


def changed(**edits):
    files = dict(FILES)
    for rel, fn in edits.items():
        rel = rel.replace("__", "/").replace("_dot_", ".")
        files[rel] = fn(files.get(rel, ""))
    return files


def main():
    results = [
        case("the intact fixture passes", FILES, 0, []),
        case("a missing backticked path fails", changed(
            README_dot_md=lambda t: t + "Also `src/core/gone.h`.\n"), 1,
            [r"README\.md:7: path not found: src/core/gone\.h"]),
        case("a missing bare path fails", changed(
            README_dot_md=lambda t: t + "And tests/field/nothing_here.cpp too.\n"), 1,
            [r"path not found: tests/field/nothing_here\.cpp"]),
        case("a placeholder that matches nothing fails", changed(
            README_dot_md=lambda t: t + "Runs in `src/runs/<name>_run.h`.\n"), 1,
            [r"path not found: src/runs/<name>_run\.h"]),
        case("a brace with one missing alternative fails", changed(
            README_dot_md=lambda t: t + "See `src/field/field.{h,cpp}`.\n"), 1,
            [r"path not found: src/field/field\.\{h,cpp\}"]),
        case("a stage-relative source file that is gone fails", changed(
            docs__other_dot_md=lambda t: t + "The old `view/ideal_mla.h`.\n"), 1,
            [r"docs/other\.md:\d+: source file not found under src/ or tests/: view/ideal_mla\.h"]),
        case("a missing anchor fails", changed(
            docs__other_dot_md=lambda t: t + "[gone](pipeline.md#no-such-heading)\n"), 1,
            [r"anchor not found: pipeline\.md#no-such-heading"]),
        case("a broken relative link fails", changed(
            docs__other_dot_md=lambda t: t + "[design](design.md)\n"), 1,
            [r"docs/other\.md:\d+: link target not found: design\.md"]),
        case("a stage map with a wrong link fails", changed(
            docs__pipeline_dot_md=lambda t: t.replace("| `field` | `core` |", "| `field` | `core`, `runs` |")),
            1, [r"stage 'field' links differ: docs: core, runs; CMakeLists\.txt:\d+: core"]),
        case("a stage missing from the docs fails", changed(
            docs__pipeline_dot_md=lambda t: t.replace("| `runs` | `field`, `core` |\n", "")), 1,
            [r"stage 'runs' is missing from the stage map"]),
        case("a stage the build does not have fails", changed(
            CMakeLists_dot_txt=lambda t: t.replace("inim_stage(runs inim_field inim_core ${SOME_LIBRARY} PkgConfig::OIIO)\n", "")),
            1, [r"stage 'runs' in the docs' stage map is not an inim_stage"]),
        case("no stage map fails", changed(
            docs__pipeline_dot_md=lambda t: t.split("## Stage libraries")[0]), 1,
            [r"docs/pipeline\.md: no stage/link table"]),
    ]
    failed = results.count(False)
    print(f"{len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
