#!/usr/bin/env python3
"""The module graph of src/: each folder is a module that declares the modules it uses (CMake's
im_module, cmake/modules.cmake), and this checks the code against the declarations:

  (a) an object file of a module refers to a symbol (nm) defined in a module it does not declare;
  (b) a file of a module includes a header of a module it does not declare;
  (c) the declared graph has a cycle;
  (d) a module declares a module it uses nothing of (the declarations say what the code does).

Usage: module_graph.py MODULES.json          check; exit 1 naming each fault (nm: $NM, else nm)
       module_graph.py --layers MODULES.json print the graph found in the code, by longest-path layer

MODULES.json is written by CMake into the build folder: for each module its name, the modules it
uses, the public headers (include/indentmap/) it owns, its sources and its object files.
"""
import json
import os
import re
import subprocess
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
# nm -P: global definitions in code, data, read-only data, BSS and common blocks.
DEFINED_TYPES = set("TDBRCGSVW")


def load(path):
    with open(path, encoding="utf-8") as stream:
        description = json.load(stream)
    modules = {module["name"]: module for module in description["modules"]}
    for module in modules.values():
        module["objects"] = [o for o in module["objects"] if o]
    return description["source_dir"], modules


def header_owners(modules):
    owners = {}
    for name, module in modules.items():
        for header in module["headers"]:
            owners["indentmap/" + header] = name
    return owners


def module_files(source_dir, name, module):
    """The sources built into the module, the headers beside them and its public headers."""
    folder = os.path.join(source_dir, "src", name)
    headers = sorted(os.path.join(folder, f) for f in os.listdir(folder) if f.endswith(".h"))
    public = [os.path.join(source_dir, "include", "indentmap", h) for h in module["headers"]]
    return module["sources"] + headers + [p for p in public if os.path.exists(p)]


def include_edges(source_dir, modules):
    """(module, used module, 'file:line includes HEADER') for each include of another module."""
    owners = header_owners(modules)
    edges = []
    for name, module in modules.items():
        for path in module_files(source_dir, name, module):
            with open(path, encoding="utf-8", errors="replace") as stream:
                for number, line in enumerate(stream, 1):
                    match = INCLUDE.match(line)
                    if not match:
                        continue
                    header = match.group(1)
                    owner = owners.get(header)
                    if owner is None and "/" in header and header.split("/")[0] in modules:
                        owner = header.split("/")[0]
                    if owner is not None and owner != name:
                        where = os.path.relpath(path, source_dir)
                        edges.append((name, owner, f"{where}:{number} includes {header}"))
    return edges


def nm_symbols(objects):
    """{object: (defined names, undefined names)} of global symbols, from one run of nm."""
    symbols = {obj: (set(), set()) for obj in objects}
    command = [os.environ.get("NM") or "nm", "-P", "-A"] + list(objects)
    output = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    for line in output.splitlines():
        # "OBJECT: NAME TYPE [VALUE SIZE]"
        obj, _, rest = line.rpartition(": ")
        fields = rest.split()
        if obj not in symbols or len(fields) < 2:
            continue
        if fields[1] == "U":
            symbols[obj][1].add(fields[0])
        elif fields[1] in DEFINED_TYPES:
            symbols[obj][0].add(fields[0])
    return symbols


def object_name(obj):
    """src/formats/units.c for .../im_formats.dir/src/formats/units.c.o."""
    marker = obj.find(".dir/")
    name = obj[marker + 5:] if marker >= 0 else os.path.basename(obj)
    return name[:-2] if name.endswith(".o") else name


def symbol_edges(modules):
    """(module, used module, 'object uses SYMBOL') for each reference into another module."""
    symbols = nm_symbols([o for m in modules.values() for o in m["objects"]])
    definer = {}
    for name, module in modules.items():
        for obj in module["objects"]:
            for symbol in symbols[obj][0]:
                definer[symbol] = name
    edges = []
    for name, module in modules.items():
        for obj in module["objects"]:
            for symbol in sorted(symbols[obj][1]):
                owner = definer.get(symbol)
                if owner is not None and owner != name:
                    edges.append((name, owner, f"{object_name(obj)} uses {symbol}"))
    return edges


def strongly_connected(graph):
    """Tarjan's components of {node: set of successors}, each a sorted list."""
    index, low, stack, on_stack, components = {}, {}, [], set(), []

    def visit(node):
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for successor in sorted(graph[node]):
            if successor not in index:
                visit(successor)
                low[node] = min(low[node], low[successor])
            elif successor in on_stack:
                low[node] = min(low[node], index[successor])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            components.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return components


def cycles(graph):
    return [c for c in strongly_connected(graph) if len(c) > 1]


def layers(graph):
    """{node: longest path to a leaf} over the graph with each cycle taken as one node."""
    component_of = {}
    for component in strongly_connected(graph):
        for node in component:
            component_of[node] = tuple(component)
    depth = {}

    def level(component):
        if component not in depth:
            # the components form an acyclic graph: edges inside a cycle do not count
            below = {component_of[s] for n in component for s in graph[n]} - {component}
            depth[component] = 1 + max((level(c) for c in below), default=-1)
        return depth[component]

    return {node: level(component_of[node]) for node in graph}


def found_graph(edges, modules):
    graph = {name: set() for name in modules}
    for user, used, _ in edges:
        graph[user].add(used)
    return graph


def check(source_dir, modules):
    faults = []
    declared = {name: set(m["uses"]) for name, m in modules.items()}
    for name, uses in declared.items():
        for used in sorted(uses - set(modules)):
            faults.append(f"module {name} declares {used}, which is no module of this build")
    for cycle in cycles({n: u & set(modules) for n, u in declared.items()}):
        faults.append("the declared graph has a cycle through " + ", ".join(cycle))
    edges = symbol_edges(modules) + include_edges(source_dir, modules)
    for user, used, evidence in edges:
        if used not in declared[user]:
            faults.append(f"{evidence} of module {used}, which module {user} does not declare")
    found = found_graph(edges, modules)
    for name, uses in sorted(declared.items()):
        for used in sorted((uses & set(modules)) - found[name]):
            faults.append(f"module {name} declares {used} but uses nothing of it")
    return faults


def print_layers(source_dir, modules):
    graph = found_graph(symbol_edges(modules) + include_edges(source_dir, modules), modules)
    level = layers(graph)
    for depth in range(max(level.values()), -1, -1):
        names = sorted(n for n in graph if level[n] == depth)
        print(f"{depth:2d} " + ", ".join(names))
    print()
    width = max(len(n) for n in graph)
    for name in sorted(graph, key=lambda n: (level[n], n)):
        print(f"{name:<{width}} -> " + (", ".join(sorted(graph[name])) or "(none)"))
    for cycle in cycles(graph):
        print("cycle: " + ", ".join(cycle))


def main(argv):
    if len(argv) == 3 and argv[1] == "--layers":
        print_layers(*load(argv[2]))
        return 0
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    source_dir, modules = load(argv[1])
    faults = check(source_dir, modules)
    for fault in faults:
        print(fault, file=sys.stderr)
    if faults:
        print(f"{len(faults)} faults in the module graph (cmake/modules.cmake declares it)", file=sys.stderr)
        return 1
    print(f"module graph: {len(modules)} modules as declared, no cycle")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
