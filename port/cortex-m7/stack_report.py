#!/usr/bin/env python3
"""Worst-case stack per public kernel entry point, and a recursion check, from gcc's call graphs.

Reads the .ci files written by `arm-none-eabi-gcc -fcallgraph-info=su` (one per kernel source; VCG
format: nodes with their frame size, edges caller -> callee). Prints, for every `ogk_*` function, its
own frame and the deepest path through the kernel's call graph. Exits 1 if the graph has a cycle
(recursion is forbidden in kernel/) or a frame is dynamic or bounded rather than static. Calls leaving
the graph (libm, libc) are listed with zero cost: they are outside the kernel's control and small on
newlib. A call through a function pointer (gcc's `__indirect_call`) may reach any kernel function whose
address the kernel's objects take (port/profile/address_taken.py: the NMPC problems' callback tables, the
MPSP right-hand sides): it costs the deepest of them, so the bound holds for the kernel's own problems; a
caller's own callback (an RK4 problem, an ogk/ocp.h problem of its own) adds its stack, which the caller
supplies.

Usage: stack_report.py [--objdump OBJDUMP --objects OBJ...] -- CI_FILE...
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "profile"))
from address_taken import address_taken  # noqa: E402

NODE = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"(.*)\}')
EDGE = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')
FRAME = re.compile(r"\\n(\d+) bytes \((static|dynamic|bounded)[^)]*\)")


def parse(paths: list[Path]) -> tuple[dict[str, tuple[int, str]], dict[str, set[str]]]:
    frames: dict[str, tuple[int, str]] = {}
    edges: dict[str, set[str]] = {}
    for path in paths:
        for line in path.read_text().splitlines():
            m = NODE.search(line)
            if m and "shape : ellipse" not in m.group(3):
                f = FRAME.search(m.group(2))
                if f:
                    frames[m.group(1)] = (int(f.group(1)), f.group(2))
                continue
            e = EDGE.search(line)
            if e:
                edges.setdefault(e.group(1), set()).add(e.group(2))
    return frames, edges


def resolve(name: str, frames: dict[str, tuple[int, str]]) -> str | None:
    """External references use the plain name; definitions of static functions carry a file prefix."""
    if name in frames:
        return name
    return None


def indirect_targets(frames: dict[str, tuple[int, str]], taken: set[str]) -> set[str]:
    """The graph's nodes (static functions carry a file prefix) whose function's address is taken."""
    return {n for n in frames if n.split(":")[-1] in taken}


def main(argv: list[str]) -> int:
    objdump, objects, ci = "", [], []
    args = argv[1:]
    if "--" in args:
        opts, ci = args[:args.index("--")], args[args.index("--") + 1:]
        objdump = opts[opts.index("--objdump") + 1]
        objects = [Path(o) for o in opts[opts.index("--objects") + 1:]]
    else:
        ci = args
    frames, edges = parse([Path(p) for p in ci])
    if objects:
        # every call through a pointer may reach every address-taken kernel function
        targets = indirect_targets(frames, address_taken(objdump, objects))
        for node, callees in edges.items():
            if "__indirect_call" in callees:
                callees.discard("__indirect_call")
                callees.update(t for t in targets if t != node)
    problems = [f"{n}: {kind} frame" for n, (_, kind) in frames.items() if kind != "static"]
    external: set[str] = set()
    # Iterative DFS with colours: finds cycles and computes the deepest stack below each node.
    depth: dict[str, int] = {}
    path_of: dict[str, list[str]] = {}
    for root in sorted(frames):
        if root in depth:
            continue
        stack: list[tuple[str, int]] = [(root, 0)]
        on_path: set[str] = set()
        while stack:
            node, state = stack.pop()
            if state == 0:
                if node in depth:
                    continue
                if node in on_path:
                    problems.append(f"recursion through {node}")
                    continue
                on_path.add(node)
                stack.append((node, 1))
                for callee in sorted(edges.get(node, ())):
                    target = resolve(callee, frames)
                    if target is None:
                        external.add(callee)
                    elif target in on_path:
                        problems.append(f"recursion: {node} -> {target}")
                    elif target not in depth:
                        stack.append((target, 0))
            else:
                on_path.discard(node)
                best, best_path = 0, []
                for callee in edges.get(node, ()):
                    target = resolve(callee, frames)
                    if target is not None and target in depth and depth[target] > best:
                        best, best_path = depth[target], path_of[target]
                depth[node] = frames[node][0] + best
                path_of[node] = [node] + best_path
    print(f"{'entry point':34s} {'own [B]':>8s} {'worst [B]':>10s}  deepest path")
    for name in sorted(n for n in frames if n.startswith("ogk_")):
        chain = " > ".join(p.split(":")[-1] for p in path_of[name][1:4])
        print(f"{name:34s} {frames[name][0]:8d} {depth[name]:10d}  {chain}")
    print(f"outside the graph (libm/libc, counted as 0): {', '.join(sorted(external)) or 'none'}")
    if problems:
        for p in problems:
            print(f"STACK CHECK FAILED: {p}")
        return 1
    print(f"stack check: {len(frames)} functions, no recursion, every frame static")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
