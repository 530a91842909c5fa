"""The import graph of tca/: no module imports the project's other packages (fem, mesher, pipelines, benchmarks,
tests), and the imports among tca modules have no cycle."""

import ast
from pathlib import Path

TCA = Path(__file__).resolve().parents[2] / "tca"


def _modules() -> dict[str, ast.Module]:
    out = {}
    for p in sorted(TCA.rglob("*.py")):
        parts = p.relative_to(TCA.parent).with_suffix("").parts
        out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = ast.parse(p.read_text(encoding="utf-8"))
    return out


def _targets(node) -> list[str]:
    """Modules named by an import statement (absolute imports: tca uses no relative ones)."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names]
    assert node.level == 0, "relative import"
    return [node.module] + [f"{node.module}.{a.name}" for a in node.names]


def test_tca_imports_nothing_of_the_other_packages():
    bad = [(m, t) for m, tree in _modules().items() for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom))
           for t in _targets(n) if t.split(".")[0] in ("fem", "mesher", "pipelines", "benchmarks", "tests")]
    assert not bad


def test_no_import_cycle_among_tca_modules():
    mods = _modules()
    # module-level imports (a function-level import runs later, but would hide a cycle: counted too)
    edges = {m: {t for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom)) for t in _targets(n)
                 if t in mods and t != m} for m, tree in mods.items()}
    state: dict[str, int] = {}  # 1 on the path, 2 done

    def visit(m, path):
        state[m] = 1
        for t in sorted(edges[m]):
            assert state.get(t) != 1, " -> ".join(path + [m, t])
            if t not in state:
                visit(t, path + [m])
        state[m] = 2

    for m in sorted(mods):
        if m not in state:
            visit(m, [])
