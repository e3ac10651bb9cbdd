#!/usr/bin/env python3
"""Checks that every #include in lib/ follows the layer order written in README.md.

The README's block between `<!-- layers -->` and `<!-- /layers -->` lists each layer of lib/ with
the layers it builds on ("bsp: kernel mesh"). A file of layer L may include
  - any header of L itself;
  - a public header (directly in lib/<M>/, not in a subfolder) of a layer M that L builds on,
    directly or through other layers.
Anything else is an include that goes up or sideways, or reaches into another layer's internals.
Exit status 1 (with file:line: messages) if any include breaks the order, 0 otherwise.
"""
import pathlib
import re
import sys

root = pathlib.Path(__file__).resolve().parent.parent
readme = (root / "README.md").read_text()
block = re.search(r"<!-- layers -->(.*?)<!-- /layers -->", readme, re.S)
if not block:
    sys.exit("check_layers: README.md has no <!-- layers --> block")

deps = {}
for line in block.group(1).splitlines():
    m = re.match(r"\s*([a-z_]+):\s*([a-z_ ]*)$", line.strip("` "))
    if m:
        deps[m.group(1)] = m.group(2).split()
for layer, below in deps.items():
    for b in below:
        if b not in deps:
            sys.exit(f"check_layers: README.md: layer '{layer}' builds on unknown layer '{b}'")


def reachable(layer):
    seen, stack = set(), list(deps[layer])
    while stack:
        x = stack.pop()
        if x == layer:
            sys.exit(f"check_layers: README.md: the layer order has a cycle through '{layer}'")
        if x not in seen:
            seen.add(x)
            stack.extend(deps[x])
    return seen


below = {layer: reachable(layer) for layer in deps}
lib = root / "lib"
folders = {p.name for p in lib.iterdir() if p.is_dir()}
problems = []
for missing in sorted(folders - set(deps)):
    problems.append(f"lib/{missing}: a layer the README's layer order does not list")

include = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/([^"]+)"')
for path in sorted(lib.rglob("*")):
    if path.suffix not in (".hpp", ".cpp"):
        continue
    layer = path.relative_to(lib).parts[0]
    if layer not in deps:
        continue
    for number, text in enumerate(path.read_text().splitlines(), 1):
        m = include.match(text)
        if not m or m.group(1) not in deps:
            continue
        target, rest = m.group(1), m.group(2)
        where = f"{path.relative_to(root)}:{number}"
        if target == layer:
            continue
        if target not in below[layer]:
            problems.append(f"{where}: error: {layer} includes {target}/{rest}, but {layer} does not build on {target}")
        elif "/" in rest:
            problems.append(f"{where}: error: {layer} includes {target}/{rest}, an internal header of {target}")

for p in problems:
    print(p)
print(f"check_layers: {len(deps)} layers, {'%d problem(s)' % len(problems) if problems else 'every include follows the order'}")
sys.exit(1 if problems else 0)
