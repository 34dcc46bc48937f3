#!/usr/bin/env python3
"""Checks that the Markdown documentation cites only what exists.

Usage: check_docs.py REPO_ROOT

1. Every repository path cited in a Markdown file (tracked, or new and not ignored) (in backticks, in Markdown links or
   as a bare token) exists. A path counts when it starts with a top-level folder of the
   repository (src/, tests/, docs/, ...) or is a top-level file (README.md, CMakeLists.txt,
   CONTRIBUTING.md); a relative Markdown link is resolved against its own file. A C++ file
   cited by its stage-relative path (`field/field.h`) must exist under src/ or tests/.
   Placeholders and globs (<name>, {h,cpp}, *, ...) are patterns that must match at least
   one path (every alternative of a brace must). What a command writes (out/..., build/...,
   the argument of --out) is not a repository path. An anchor (#section) in a link to a
   Markdown file must be a heading of that file (GitHub's slugs).
2. The stage/link table of docs/pipeline.md equals the inim_stage(...) lines of
   CMakeLists.txt (the inim_<stage> links only).

Prints one line per problem and a last line "N passed, M failed"; exits 1 on any failure.
Python 3 standard library only.
"""

import glob
import os
import re
import subprocess
import sys
import unicodedata

TOP_FOLDERS = ("src", "tests", "docs", "scripts", "optics", "spectra", "scenes",
               "validation", "fuzz", "web", ".ci")
TOP_FILES = ("README.md", "CMakeLists.txt", "CONTRIBUTING.md")
SKIP_DIRS = {"build", "out", "node_modules", ".git"}
CPP_EXTS = (".h", ".hpp", ".cpp", ".cc")
STAGE_MAP_FILE = "docs/pipeline.md"

# A path token: no spaces, quotes, brackets or table bars; a brace group {a,b} may hold commas.
_PATH_CHARS = r"(?:\{[^}\s]*\}|[^\s`'\"()\[\]|,;{}])"
_TOP = "|".join(re.escape(f) for f in TOP_FOLDERS)
_TOPF = "|".join(re.escape(f) for f in TOP_FILES)
# Not after a word character, a slash, a dot, a hyphen or '<' (so ../x, a/src/b, URLs are not
# taken); ".ci" needs its own lookbehind because it starts with a dot.
BARE_RE = re.compile(
    r"(?<![\w/.<>@$-])((?:(?:" + _TOP + r")/" + _PATH_CHARS + r"*)|(?:" + _TOPF + r")(?:#[\w-]+)?)"
    r"(?![\w.-]*\w)")
# A stage-relative C++ file: word/…/name.h (not after a slash or dot).
CPP_RE = re.compile(r"(?<![\w/.<>@$-])([a-z_][\w]*/" + _PATH_CHARS + r"*?\.(?:h|hpp|cpp|cc))(?![\w.])")
LINK_RE = re.compile(r"(!?)\[((?:[^\[\]]|\[[^\]]*\])*)\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
OUTPUT_OPTION_RE = re.compile(r"--out(?:=|\s+)$")


class Checker:
    def __init__(self, root):
        self.root = os.path.abspath(root)
        self.passed = 0
        self.failed = 0
        self._headings = {}

    # ---- reporting -------------------------------------------------------------------------
    def ok(self):
        self.passed += 1

    def fail(self, where, message):
        self.failed += 1
        print(f"{where}: {message}")

    # ---- files -----------------------------------------------------------------------------
    def markdown_files(self):
        try:
            out = subprocess.run(["git", "ls-files", "-z", "--cached", "--others",
                                  "--exclude-standard", "--", "*.md"], cwd=self.root,
                                 capture_output=True, check=True)
            files = [f for f in out.stdout.decode("utf-8").split("\0") if f]
            # A file removed from the work tree but still in the index is not a document.
            files = [f for f in files if os.path.isfile(os.path.join(self.root, f))]
            if files:
                return sorted(files)
        except (OSError, subprocess.CalledProcessError):
            pass
        found = []
        for dirpath, dirnames, filenames in os.walk(self.root):
            rel = os.path.relpath(dirpath, self.root)
            dirnames[:] = sorted(d for d in dirnames
                                 if d not in SKIP_DIRS and not (rel == "." and d.startswith("build")))
            for name in filenames:
                if name.endswith(".md"):
                    found.append(os.path.normpath(os.path.join(rel, name)))
        return sorted(found)

    # ---- patterns --------------------------------------------------------------------------
    @staticmethod
    def is_pattern(path):
        return any(c in path for c in "<>{}*?") or "..." in path or "…" in path

    @staticmethod
    def expand_braces(path):
        m = re.search(r"\{([^{}]*)\}", path)
        if not m:
            return [path]
        out = []
        for alt in m.group(1).split(","):
            out.extend(Checker.expand_braces(path[:m.start()] + alt + path[m.end():]))
        return out

    @staticmethod
    def to_glob(path):
        g = re.sub(r"<[^<>]*>", "*", path)
        g = g.replace("...", "*").replace("…", "*")
        g = re.sub(r"\*{3,}", "**", g)
        return g

    def exists(self, rel, base=None):
        """rel: a repository path (a pattern allowed), relative to base (default: the root)."""
        base = self.root if base is None else base
        if not self.is_pattern(rel):
            return os.path.exists(os.path.normpath(os.path.join(base, rel)))
        for alt in self.expand_braces(rel):
            pattern = os.path.join(base, self.to_glob(alt))
            if not glob.glob(pattern, recursive=True):
                return False
        return True

    # ---- anchors ---------------------------------------------------------------------------
    @staticmethod
    def slug(text):
        text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links: their text
        text = re.sub(r"<[^>]+>", "", text)                    # inline HTML
        text = text.strip().lower()
        out = []
        for ch in text:
            cat = unicodedata.category(ch)
            if ch in " -":
                out.append("-")
            elif ch == "_" or cat[0] in "LN" or cat == "Mn":
                out.append(ch)
        return "".join(out)

    def headings(self, path):
        if path in self._headings:
            return self._headings[path]
        anchors = set()
        counts = {}
        in_fence = False
        try:
            with open(path, encoding="utf-8") as f:
                lines = f.read().splitlines()
        except OSError:
            lines = []
        for line in lines:
            if re.match(r"^\s*(```|~~~)", line):
                in_fence = not in_fence
                continue
            if in_fence:
                continue
            for m in re.finditer(r"<a\s+(?:name|id)=\"([^\"]+)\"", line):
                anchors.add(m.group(1))
            m = re.match(r"^ {0,3}#{1,6}\s+(.*?)\s*#*\s*$", line)
            if m:
                s = self.slug(m.group(1))
                n = counts.get(s, 0)
                counts[s] = n + 1
                anchors.add(s if n == 0 else f"{s}-{n}")
        self._headings[path] = anchors
        return anchors

    def check_anchor(self, where, target_abs, anchor, shown):
        if not anchor:
            return
        if not target_abs.endswith(".md") or not os.path.isfile(target_abs):
            return
        if anchor in self.headings(target_abs):
            self.ok()
        else:
            self.fail(where, f"anchor not found: {shown} (no heading '#{anchor}' in "
                             f"{os.path.relpath(target_abs, self.root)})")

    # ---- one Markdown file -----------------------------------------------------------------
    def check_file(self, rel):
        path = os.path.join(self.root, rel)
        base = os.path.dirname(path)
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
        for number, line in enumerate(lines, 1):
            where = f"{rel}:{number}"
            # Markdown links (and images): relative to this file, or an anchor in it.
            rest = line
            for m in LINK_RE.finditer(line):
                target = m.group(3)
                if re.match(r"^[a-zA-Z][\w+.-]*:", target) or target.startswith("//"):
                    continue  # a URL
                file_part, _, anchor = target.partition("#")
                if not file_part:
                    self.check_anchor(where, path, anchor, target)
                    continue
                if file_part.startswith("/"):
                    target_abs = os.path.normpath(os.path.join(self.root, file_part.lstrip("/")))
                    rel_base = self.root
                    file_rel = file_part.lstrip("/")
                else:
                    target_abs = os.path.normpath(os.path.join(base, file_part))
                    rel_base = base
                    file_rel = file_part
                if self.exists(file_rel, rel_base):
                    self.ok()
                    self.check_anchor(where, target_abs, anchor, target)
                else:
                    self.fail(where, f"link target not found: {target}")
            rest = LINK_RE.sub(lambda m: m.group(1) + "[" + m.group(2) + "]()", line)
            # Bare and backticked repository paths, relative to the root.
            for m in BARE_RE.finditer(rest):
                if OUTPUT_OPTION_RE.search(rest[:m.start()]):
                    continue  # what a command writes (--out DIR) is not a repository path
                token = m.group(1).rstrip(".:")
                file_part, _, anchor = token.partition("#")
                if self.exists(file_part):
                    self.ok()
                    self.check_anchor(where, os.path.join(self.root, file_part), anchor, token)
                else:
                    self.fail(where, f"path not found: {token}")
            # Stage-relative C++ files: `field/field.h` is src/field/field.h (or tests/...).
            for m in CPP_RE.finditer(rest):
                token = m.group(1)
                if token.split("/")[0] in TOP_FOLDERS:
                    continue
                if self.exists("src/" + token) or self.exists("tests/" + token):
                    self.ok()
                else:
                    self.fail(where, f"source file not found under src/ or tests/: {token}")

    # ---- the stage map ---------------------------------------------------------------------
    @staticmethod
    def stage_names(cell):
        cell = cell.replace("`", "").strip()
        if cell.lower() in ("", "(none)", "none", "—", "-", "–"):
            return set()
        names = set()
        for part in re.split(r"[,\s]+", cell):
            part = part.strip()
            if not part or part.lower() in ("(none)", "none", "and"):
                continue
            names.add(part[5:] if part.startswith("inim_") else part)
        return names

    def docs_stage_map(self):
        """{stage: (links, line)} from the table of docs/pipeline.md whose header names a
        stage column and a links column; None when there is no such table."""
        path = os.path.join(self.root, STAGE_MAP_FILE)
        try:
            with open(path, encoding="utf-8") as f:
                lines = f.read().splitlines()
        except OSError:
            return None
        for i, line in enumerate(lines):
            cells = [c.strip().lower() for c in line.strip().strip("|").split("|")]
            if not line.lstrip().startswith("|") or len(cells) < 2:
                continue
            if "stage" not in cells[0] or not any("link" in c for c in cells[1:]):
                continue
            col = next(j for j, c in enumerate(cells) if j > 0 and "link" in c)
            table = {}
            for j in range(i + 2, len(lines)):
                row = lines[j].strip()
                if not row.startswith("|"):
                    break
                cols = [c.strip() for c in row.strip("|").split("|")]
                name = cols[0].replace("`", "").strip()
                name = name[5:] if name.startswith("inim_") else name
                table[name] = (self.stage_names(cols[col]) if col < len(cols) else set(), j + 1)
            return table
        return None

    def cmake_stage_map(self):
        path = os.path.join(self.root, "CMakeLists.txt")
        table = {}
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for m in re.finditer(r"^[ \t]*inim_stage\(\s*([\w]+)([^)]*)\)", text, re.M):
            line = text.count("\n", 0, m.start()) + 1
            deps = {d[5:] for d in m.group(2).split() if re.fullmatch(r"inim_\w+", d)}
            table[m.group(1)] = (deps, line)
        return table

    def check_stage_map(self):
        docs = self.docs_stage_map()
        if docs is None:
            self.fail(STAGE_MAP_FILE, "no stage/link table (a table whose header has a "
                                      "'stage' column and a 'links' column)")
            return
        cmake = self.cmake_stage_map()
        if not cmake:
            self.fail("CMakeLists.txt", "no inim_stage(...) lines")
            return

        def show(s):
            return ", ".join(sorted(s)) if s else "(none)"

        for name in sorted(set(docs) | set(cmake)):
            if name not in cmake:
                self.fail(f"{STAGE_MAP_FILE}:{docs[name][1]}",
                          f"stage '{name}' in the docs' stage map is not an inim_stage in "
                          f"CMakeLists.txt (docs: {show(docs[name][0])})")
            elif name not in docs:
                self.fail(f"CMakeLists.txt:{cmake[name][1]}",
                          f"stage '{name}' is missing from the stage map of {STAGE_MAP_FILE} "
                          f"(CMakeLists.txt: {show(cmake[name][0])})")
            elif docs[name][0] != cmake[name][0]:
                self.fail(f"{STAGE_MAP_FILE}:{docs[name][1]}",
                          f"stage '{name}' links differ: docs: {show(docs[name][0])}; "
                          f"CMakeLists.txt:{cmake[name][1]}: {show(cmake[name][0])}")
            else:
                self.ok()

    def run(self):
        for rel in self.markdown_files():
            self.check_file(rel)
        self.check_stage_map()
        print(f"{self.passed} passed, {self.failed} failed")
        return 1 if self.failed else 0


def main(argv):
    if len(argv) != 2 or not os.path.isdir(argv[1]):
        print("usage: check_docs.py REPO_ROOT", file=sys.stderr)
        return 2
    return Checker(argv[1]).run()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
