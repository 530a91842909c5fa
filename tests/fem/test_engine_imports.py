"""fem is a gear-free engine: no module of it imports tca, mesher, pipelines or benchmarks (docs/architecture.md)."""

import ast
from pathlib import Path

import fem

PROJECT = {"tca", "mesher", "pipelines", "benchmarks", "tests"}


def test_fem_imports_nothing_of_the_project_but_itself():
    root = Path(fem.__file__).parent
    found = []
    for path in sorted(root.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(), str(path))):  # function-level imports too
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0:
                names = [node.module]
            else:
                continue
            found += [f"{path.relative_to(root.parent)}:{node.lineno} {n}" for n in names if n.split(".")[0] in PROJECT]
    assert not found, found
