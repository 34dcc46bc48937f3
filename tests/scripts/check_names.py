#!/usr/bin/env python3
"""Fails on any name a Python file loads that is never bound where it could be seen: not a
builtin, not imported, assigned or defined in the module, nor bound in an enclosing function.
Stdlib only (ast), so it runs without the file's own dependencies (torch, Nerfstudio).

    python3 tests/scripts/check_names.py scripts/nerfstudio_colors.py [...]

It first checks itself on a snippet that uses Path without importing it (as an earlier
Nerfstudio recipe did), so it cannot pass by finding nothing.
"""
import ast
import builtins
import sys

SCOPES = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)


def bound_here(scope):
    """Names bound directly in `scope` (not inside nested functions or classes)."""
    names = set()
    if isinstance(scope, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
        a = scope.args
        for arg in a.posonlyargs + a.args + a.kwonlyargs + [a.vararg, a.kwarg]:
            if arg is not None:
                names.add(arg.arg)
    stack = list(ast.iter_child_nodes(scope)) if not isinstance(scope, ast.Lambda) else [scope.body]
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
            stack.extend(node.decorator_list)
            continue
        if isinstance(node, ast.Lambda):
            continue
        if isinstance(node, ast.Name) and isinstance(node.ctx, (ast.Store, ast.Del)):
            names.add(node.id)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            for alias in node.names:
                names.add((alias.asname or alias.name).split(".")[0])
        elif isinstance(node, ast.ExceptHandler) and node.name:
            names.add(node.name)
        elif isinstance(node, (ast.Global, ast.Nonlocal)):
            names.update(node.names)
        elif isinstance(node, ast.arg):
            names.add(node.arg)
        stack.extend(ast.iter_child_nodes(node))
    return names


def undefined_names(source, filename="<source>"):
    """[(line, name)] of loads that no visible scope binds."""
    tree = ast.parse(source, filename)
    problems = []

    def visit(scope, visible):
        visible = visible | bound_here(scope)
        stack = list(ast.iter_child_nodes(scope)) if not isinstance(scope, ast.Lambda) else [scope.body]
        while stack:
            node = stack.pop()
            if isinstance(node, SCOPES):
                # Defaults and decorators are evaluated in this scope; the body in its own.
                if not isinstance(node, ast.ClassDef):
                    stack.extend(node.args.defaults + [d for d in node.args.kw_defaults if d])
                if not isinstance(node, ast.Lambda):
                    stack.extend(node.decorator_list)
                visit(node, visible if not isinstance(node, ast.ClassDef) else visible)
                continue
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) and node.id not in visible:
                problems.append((node.lineno, node.id))
            stack.extend(ast.iter_child_nodes(node))

    visit(tree, set(dir(builtins)) | {"__file__", "__name__", "__doc__"})
    return sorted(problems)


def main(paths):
    bad = "import json\n\ndef f(p):\n    return json.loads(Path(p).read_text())\n"
    if undefined_names(bad) != [(4, "Path")]:
        print("check_names: self-test failed: Path used without import was not reported")
        return 1
    status = 0
    for path in paths:
        with open(path, encoding="utf-8") as f:
            for line, name in undefined_names(f.read(), path):
                print(f"{path}:{line}: name '{name}' is used but never defined or imported")
                status = 1
    if status == 0:
        print(f"check_names: {len(paths)} file(s), every name defined or imported")
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
