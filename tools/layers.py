#!/usr/bin/env python3
"""The layers of the code and the calls and includes that cross them (issue 47, "The code's shape").

Each source file belongs to the layer of its folder, src/<folder>/, lowest first:
  base       (src/base)      kernel, materials, dimensions, CSR matrices, reference data, reading options, version
  particles  (src/particles) the particle arrays and the parallel machinery: grid, cells, decomposition, halo,
                             exchange, and the neighbourhood that brings them up to date after particles move
  physics    (src/physics, src/fluid, src/solid) the context they share (physics.h), the fluids (WCSPH, ISPH, the pressure equation, walls, operators), the solids
  io         (src/io)        snapshots, checkpoints, output directories, disk space
  run        (src/run)       the driver (sim), the run guard, the size guard, the program's calls (program.c:
                             SPHFSIInitialize/Run/Finalize), the scene registry, the scene's view of the run (sim_scene.c)
  build      (src/build)     the builders behind <sphfsi/scene.h> and <sphfsi/shapes.h>: lattices, boxes, tanks, shapes
  scenes     (src/scenes)    the built-in scenes, written against the public interface (include/) only
  app        (src/app)       bin/sphfsi's main
A file may call and include files of its own layer and of the layers below.  A call or an include
from a lower layer into a higher one is "upward": it ties the lower layer to the driver or to a
module above it.  This script lists them, and the cycles of the file-level call graph.

It fails (status 1) when an upward call or include, or a call cycle, is not in tools/layers_known.txt, or when a line
of that file no longer occurs (the list only shrinks: --update rewrites it).  The file is what the
redesign of issue 47 still has to remove, one step at a time.
  tools/layers.py [--list] [--update]   (--list: every upward edge and every cycle, with its line)
"""
import glob, os, re, sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
ORDER = ["base", "particles", "physics", "io", "run", "build", "scenes", "app"]
FOLDER = {"base": "base", "particles": "particles", "physics": "physics", "fluid": "physics", "solid": "physics", "io": "io", "run": "run", "build": "build", "scenes": "scenes", "app": "app"}
# the layers that see only the public interface (include/): no "layer/module.h" include
PUBLIC_ONLY = ("scenes", "app")

# Upward edges that remain to be removed: "file -> symbol" (a call) or "file -> #include header".
KNOWN_FILE = os.path.join(ROOT, "tools", "layers_known.txt")
KNOWN = {l.strip() for l in open(KNOWN_FILE) if l.strip() and not l.startswith("#")} if os.path.exists(KNOWN_FILE) else set()


# files that are one module between them (calls among them are the module's own)
GROUP = {"csr_hypre": "csr"}


def folder(path):
    return os.path.relpath(path, ROOT).split(os.sep)[1]


def module(path):
    rel = os.path.relpath(path, ROOT)
    if rel.startswith("src/scenes/"):
        return "scene"
    stem = os.path.splitext(os.path.basename(rel))[0]
    return GROUP.get(stem, stem)


def strip(text):
    """The text without comments and string literals (kept line for line)."""
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    return re.sub(r'^(?!\s*#\s*include)[^\n]*', lambda m: re.sub(r'"(\\.|[^"\\\n])*"', '""', m.group(0)), text, flags=re.M)


def main():
    files = sorted(glob.glob(os.path.join(ROOT, "src", "*", "*.[ch]")))
    unknown = sorted({folder(f) for f in files if folder(f) not in FOLDER})
    if unknown:
        sys.exit("tools/layers.py: no layer for src/" + ", src/".join(unknown) + " (add it to FOLDER)")
    OF = {module(f): FOLDER[folder(f)] for f in files}
    # definitions other files can call: functions defined at the start of a line (not static in a .c
    # file; static inline in a header counts) and function-like macros of headers
    owner = {}
    for path in files:
        text = strip(open(path).read())
        for mt in re.finditer(r"^([A-Za-z_][\w \t\*]*?)\b(\w+)\s*\([^;{}]*?\)\s*\{", text, flags=re.M):
            if path.endswith(".c") and mt.group(1).lstrip().startswith(("static", "SPH_INLINE")):
                continue
            owner.setdefault(mt.group(2), set()).add(module(path))
        for name in re.findall(r"^\s*#\s*define\s+(\w+)\(", text, flags=re.M):
            owner.setdefault(name, set()).add(module(path))
    edges, up = {}, []
    for path in files:
        m = module(path)
        text = strip(open(path).read())
        for no, line in enumerate(text.split("\n"), 1):
            if FOLDER[folder(path)] in PUBLIC_ONLY:
                for inc in re.findall(r'#\s*include\s*"([^"]+)"', line):
                    up.append((path, no, "#include " + inc + " (not the public interface)", FOLDER[folder(path)], "internal"))
            for fold, inc in re.findall(r'#\s*include\s*"(\w+)/(\w+)\.h"', line):
                inc = "scene" if fold == "scenes" else GROUP.get(inc, inc)  # every scenes/ header is the module scene
                if inc != m and ORDER.index(OF[inc]) > ORDER.index(OF[m]):
                    up.append((path, no, "#include " + inc + ".h", OF[m], OF[inc]))
            for name in re.findall(r"\b([A-Za-z_]\w*)\s*\(", line):
                for callee in owner.get(name, ()):
                    if callee == m:
                        continue
                    edges.setdefault(m, {}).setdefault(callee, (path, no, name))
                    if ORDER.index(OF[callee]) > ORDER.index(OF[m]):
                        up.append((path, no, name, OF[m], OF[callee]))
    # cycles of the module call graph (strongly connected components, Tarjan)
    index, low, stack, on, sccs = {}, {}, [], set(), []
    def visit(v):
        index[v] = low[v] = len(index); stack.append(v); on.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                visit(w); low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            c = []
            while True:
                w = stack.pop(); on.discard(w); c.append(w)
                if w == v:
                    break
            if len(c) > 1:
                sccs.append(sorted(c))
    sys.setrecursionlimit(10000)
    for v in sorted(OF):
        if v not in index:
            visit(v)
    found = {}
    for path, no, what, a, b in up:
        found.setdefault(os.path.relpath(path, ROOT) + " -> " + what, (no, a, b))
    for c in sccs:  # a cycle is known as the set of its modules: one that grows is new
        found["cycle: " + " ".join(c)] = (0, "call", "cycle")
    if "--update" in sys.argv:
        with open(KNOWN_FILE, "w") as f:
            f.write("# Upward calls and includes still to remove (issue 47); written by tools/layers.py --update\n")
            f.writelines(k + "\n" for k in sorted(found))
        KNOWN.clear(); KNOWN.update(found)
    new = sorted(set(found) - KNOWN)
    stale = sorted(KNOWN - set(found))
    if "--list" in sys.argv:
        for k in sorted(found):
            if k.startswith("cycle: "):
                continue
            no, a, b = found[k]
            print(f"upward ({a} -> {b}): {k.replace(' -> ', ':%d -> ' % no, 1)}")
        for c in sccs:
            print("cycle: " + " <-> ".join(c))
            for a in c:
                for b, (path, no, name) in sorted(edges.get(a, {}).items()):
                    if b in c:
                        print(f"  {a} -> {b}: {os.path.relpath(path, ROOT)}:{no} {name}")
    nup = sum(not k.startswith("cycle: ") for k in found)
    print(f"layers: {nup} upward calls and includes ({len(new)} not in tools/layers_known.txt), "
          f"{len(sccs)} call cycle(s){': ' + '; '.join(' '.join(c) for c in sccs) if sccs else ''}")
    for k in new:
        print("  new: " + k + ("" if k.startswith("cycle: ") else f" ({found[k][1]} -> {found[k][2]}, line {found[k][0]})"))
    for k in stale:
        print("  no longer upward (run tools/layers.py --update): " + k)
    return 1 if new or stale else 0


if __name__ == "__main__":
    sys.exit(main())
