#!/usr/bin/env python3
"""The module graph of a crate, and its import cycles (ARCHITECTURE.md: "the dependency line").

Reads every `.rs` file under the crate's `src/`, finds the paths it names through `crate::` (in
`use` trees and in expressions, comments skipped) and `super::`, and maps each to the module that
defines it. A name re-exported at the crate root (`pub use drive::{Stats, ..}` in `lib.rs`) counts
as its defining module, so a root re-export cannot hide a cycle. Prints, for the top-level modules
and for the submodules of each top-level module, the edges and every cycle (strongly connected
component of more than one module); exits 1 if there is any cycle, so a check can run it.

    python3 scripts/module_graph.py [runtime/src] [--dot graph.dot] [--edges]

`--dot` writes the top-level graph for Graphviz.
"""

import argparse
import pathlib
import re
import sys

IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def strip_comments(text):
    """The code without `//` comments and string literals (doc links name paths too)."""
    text = re.sub(r"'(?:\\.|[^'\\])'", "' '", text)  # char literals, '"' among them
    text = re.sub(r'r(#*)".*?"\1', '""', text, flags=re.S)  # raw strings
    text = re.sub(r'"(?:\\.|[^"\\])*"', '""', text, flags=re.S)
    return "\n".join(line.split("//", 1)[0] for line in text.splitlines())


def parse_tree(text, i, prefix):
    """The leaf paths of the path or use tree starting at `text[i]`, and where it ends."""
    path = list(prefix)
    leaves = []
    while True:
        while i < len(text) and text[i] in " \n\t":
            i += 1
        if i < len(text) and text[i] == "{":
            i += 1
            while True:
                sub, i = parse_tree(text, i, path)
                leaves.extend(sub)
                while i < len(text) and text[i] in " \n\t,":
                    i += 1
                if i >= len(text) or text[i] == "}":
                    return leaves, i + 1
        m = IDENT.match(text, i)
        if not m:
            break
        name = m.group(0)
        i = m.end()
        if name != "self":
            path.append(name)
        rest = re.match(r"\s*as\s+([A-Za-z_][A-Za-z0-9_]*)", text[i:])
        if rest:
            i += rest.end()
            path.append(("as", rest.group(1)))
            break
        if text.startswith("::", i):
            i += 2
            continue
        break
    leaves.append(path)
    return leaves, i


def module_of(file, src):
    """The module path of `file` (`drive/mod.rs` is `drive`, `lib.rs` the root)."""
    parts = list(file.relative_to(src).with_suffix("").parts)
    if parts[-1] in ("mod", "lib", "main"):
        parts = parts[:-1]
    return parts


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("src", nargs="?", default="runtime/src")
    parser.add_argument("--dot")
    parser.add_argument("--edges", action="store_true", help="print every edge, with a file")
    args = parser.parse_args()
    src = pathlib.Path(args.src)
    files = sorted(src.rglob("*.rs"))
    top = {f.relative_to(src).parts[0].removesuffix(".rs") for f in files} - {"lib", "main"}

    # Root re-exports: name -> top-level module.
    root = strip_comments((src / "lib.rs").read_text() if (src / "lib.rs").exists()
                          else (src / "main.rs").read_text())
    exported = {}
    for m in re.finditer(r"\bpub use\s+", root):
        leaves, _ = parse_tree(root, m.end(), [])
        for leaf in leaves:
            names = [p for p in leaf if isinstance(p, str)]
            alias = [p[1] for p in leaf if isinstance(p, tuple)]
            if names and names[0] in top:
                exported[(alias or names)[-1]] = names[0]

    def submodule(top_name, name):
        d = src / top_name
        return d.is_dir() and ((d / f"{name}.rs").exists() or (d / name).is_dir())

    edges = {}  # (from, to) -> first file
    for f in files:
        here = module_of(f, src)
        if not here:
            continue
        text = strip_comments(f.read_text())
        targets = []
        for m in re.finditer(r"\bcrate::", text):
            for leaf in parse_tree(text, m.end(), [])[0]:
                names = [p for p in leaf if isinstance(p, str)]
                if not names:
                    continue
                if names[0] in top:
                    targets.append(names[:2])
                elif names[0] in exported:
                    targets.append([exported[names[0]]])
        # `super::x` from a file directly inside a top-level directory names a sibling.
        depth = len(here) - (0 if f.name == "mod.rs" else 1)
        for m in re.finditer(r"\bsuper::", text):
            if depth != 1 or f.name == "mod.rs" and len(here) == 1:
                continue
            for leaf in parse_tree(text, m.end(), [])[0]:
                names = [p for p in leaf if isinstance(p, str)]
                if names:
                    targets.append([here[0], names[0]])
        for target in targets:
            a, b = here[0], target[0]
            if a != b:
                edges.setdefault((a, b), f)
            elif len(here) > 1 and len(target) > 1 and submodule(a, target[1]):
                sa, sb = f"{a}::{here[1]}", f"{a}::{target[1]}"
                if sa != sb:
                    edges.setdefault((sa, sb), f)

    def cycles(nodes, pairs):
        graph = {n: [b for (a, b) in pairs if a == n] for n in nodes}
        index, low, stack, on, out = {}, {}, [], set(), []
        counter = [0]

        def visit(v):
            index[v] = low[v] = counter[0]
            counter[0] += 1
            stack.append(v)
            on.add(v)
            for w in graph[v]:
                if w not in index:
                    visit(w)
                    low[v] = min(low[v], low[w])
                elif w in on:
                    low[v] = min(low[v], index[w])
            if low[v] == index[v]:
                component = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    component.append(w)
                    if w == v:
                        break
                if len(component) > 1:
                    out.append(sorted(component))

        sys.setrecursionlimit(10000)
        for n in nodes:
            if n not in index:
                visit(n)
        return out

    found = 0
    levels = [("the crate", sorted(top), [e for e in edges if "::" not in e[0]])]
    for t in sorted(top):
        subs = sorted({x for e in edges for x in e if x.startswith(f"{t}::")})
        if subs:
            levels.append((t, subs, [e for e in edges if e[0].startswith(f"{t}::")]))
    for name, nodes, pairs in levels:
        for component in cycles(nodes, pairs):
            found += 1
            print(f"cycle in {name}: {' <-> '.join(component)}")
            for a, b in pairs:
                if a in component and b in component:
                    print(f"  {a} -> {b}  ({edges[(a, b)].relative_to(src)})")
    if args.edges:
        for (a, b), f in sorted(edges.items()):
            print(f"{a} -> {b}  ({f.relative_to(src)})")
    if args.dot:
        with open(args.dot, "w") as out:
            out.write("digraph modules {\n")
            for a, b in sorted(e for e in edges if "::" not in e[0]):
                out.write(f'  "{a}" -> "{b}";\n')
            out.write("}\n")
    print(f"{len(files)} files, {len(edges)} module edges, {found} cycles")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
