"""No import cycle between the modules of ogk, ogk_host and ogk_bindings, at any level.

import-linter's contracts (pyproject.toml) keep the layers and the families apart, but say nothing
about two modules of one package importing each other. This test builds the import graph with grimp
(the library under import-linter; it records every import, including those inside a function and
under `if TYPE_CHECKING:`) and asserts that it has no strongly connected component of more than one
module and no module importing itself.

The one exemption (the only one issue 18 allows): a package's `__init__` importing its own submodules
(an edge P -> P.sub, the usual re-export of a package's API), so that a submodule taking a name from
its package (P.sub -> P) is not reported. Today only ogk_host/binary/__init__.py imports its
submodules and none of them imports the package back: the exemption hides no cycle. Nothing else is
exempt.
"""
from __future__ import annotations

import grimp
import pytest

pytestmark = pytest.mark.req("OGK-HAR-011")

PACKAGES = ("ogk", "ogk_host", "ogk_bindings")


def _package_imports_own_submodule(importer: str, imported: str) -> bool:
    return imported.startswith(importer + ".")


def import_graph() -> dict[str, set[str]]:
    """module -> the modules of PACKAGES it imports (anywhere in its source), exempt edges removed."""
    graph = grimp.build_graph(*PACKAGES, include_external_packages=False)
    edges: dict[str, set[str]] = {}
    for module in graph.modules:
        edges[module] = {m for m in graph.find_modules_directly_imported_by(module)
                         if not _package_imports_own_submodule(module, m)}
    return edges


def strongly_connected_components(edges: dict[str, set[str]]) -> list[list[str]]:
    """Tarjan's algorithm, iterative (no recursion limit), over every node of `edges`."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    components: list[list[str]] = []
    counter = 0
    for root in sorted(edges):
        if root in index:
            continue
        work: list[tuple[str, list[str]]] = [(root, sorted(edges.get(root, ())))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, pending = work[-1]
            if pending:
                nxt = pending.pop()
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, sorted(edges.get(nxt, ()))))
                elif nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                components.append(sorted(component))
    return components


def _describe(component: list[str], edges: dict[str, set[str]]) -> str:
    members = set(component)
    inner = sorted((a, b) for a in component for b in edges[a] if b in members)
    return "cycle among " + ", ".join(component) + ": " + "; ".join(f"{a} -> {b}" for a, b in inner)


def test_scc_finder_sees_a_cycle() -> None:
    """The component finder itself: a -> b -> c -> a is one component, d alone, e -> e a self-loop."""
    edges = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set(), "e": {"e"}}
    components = strongly_connected_components(edges)
    assert sorted(components) == [["a", "b", "c"], ["d"], ["e"]]
    assert _package_imports_own_submodule("ogk.sil", "ogk.sil.plots")
    assert not _package_imports_own_submodule("ogk.sil.plots", "ogk.sil")
    assert not _package_imports_own_submodule("ogk.sil", "ogk.silly")


def test_no_import_cycle() -> None:
    edges = import_graph()
    assert any(m.startswith("ogk.missions.") for m in edges)   # the graph covers the harness
    cycles = [c for c in strongly_connected_components(edges) if len(c) > 1]
    self_imports = sorted(m for m, targets in edges.items() if m in targets)
    problems = [_describe(c, edges) for c in cycles] + [f"{m} imports itself" for m in self_imports]
    assert not problems, "\n".join(problems)
