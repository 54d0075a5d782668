#!/usr/bin/env python3
"""Checks that the source tree's include graph follows its layers, the plugin API lowest.

    check_include_layers.py --root REPO        check the repository; exit 0 when it follows the layers
    check_include_layers.py --self-test        plant one mistake of each kind in a scratch tree and
                                               check that each is reported (exit 0 when all are)

Every folder that builds a library is a layer (LAYERS below, lowest first) and may include the
headers of the layers it names and of theirs, never of one above it. An include is resolved as the
compiler would: next to the including file (quoted), then in each layer's folders. It is also
refused when
  - a header of the plugin API (plugin_api/include, the installed one) includes anything but the
    API's own headers, the standard library and Eigen: a plugin author has nothing else;
  - a plugin's CMakeLists.txt links a host library (the kernel or any library above it).
Each finding names file and line, the header and whose it is, and what to do.
"""
import argparse
import pathlib
import re
import sys
import tempfile

# name: (folders holding its headers and sources, layers it may include; theirs come along)
LAYERS = {
    "plugin_api": (("plugin_api/include", "plugin_api/simd/include"), ()),
    "io": (("io/include", "io/src"), ()),
    "geometry": (("geometry/include", "geometry/src"), ("plugin_api", "io")),
    "h5": (("h5/include", "h5/src"), ("plugin_api", "io")),
    "plugins": (("plugins",), ("plugin_api", "geometry", "h5")),
    "templates": (("templates",), ("plugin_api",)),
    "kernel": (("kernel/include", "kernel/src"), ("geometry", "h5")),
    "analysis": (("analysis/include", "analysis/src"), ("kernel",)),
    # The decomposed run labels its fragments with the analysis library's union-find
    # (shard/analysis/components.hpp): mpi is a layer above analysis and below the driver.
    "mpi": (("mpi/include", "mpi/src"), ("analysis",)),
    "bending": (("analysis/bending",), ("analysis",)),
    "measure": (("analysis/measure",), ("analysis",)),
    "driver": (("driver",), ("analysis", "mpi")),
    "apps": (("apps",), ("driver", "bending", "measure")),
    "python": (("python",), ("driver",)),
}
HOST_LAYERS = ("kernel", "mpi", "analysis", "bending", "measure", "driver", "apps", "python")
# The installed API's headers may include these beside their own (a standard header has no '.').
API_FOREIGN = re.compile(r"^(?:[a-z_]+|Eigen/\w+)$")
INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*([<"])([^>"]+)[>"]', re.MULTILINE)
HOST_LINK = re.compile(r"\bshard(?:::|_)(%s)\b" % "|".join(("kernel", "mpi", "analysis", "bending", "measure",
                                                           "driver", "app")))
SOURCE_SUFFIXES = (".hpp", ".cpp", ".h", ".cc", ".hpp.in", ".cpp.in")


def may_include(layer):
    """The layers `layer` may include: itself, those it names and theirs."""
    allowed, todo = {layer}, list(LAYERS[layer][1])
    while todo:
        below = todo.pop()
        if below not in allowed:
            allowed.add(below)
            todo.extend(LAYERS[below][1])
    return allowed


def layer_of(root, path):
    """The layer a file belongs to: the one whose folder holds it most closely."""
    rel = path.relative_to(root).as_posix()
    best = None
    for name, (folders, _) in LAYERS.items():
        for folder in folders:
            if rel.startswith(folder + "/") and (best is None or len(folder) > len(best[1])):
                best = (name, folder)
    return best[0] if best else None


def include_folders(root):
    """Every folder an include may be found in, with its layer: each layer's folders and every folder
    below them (include/ and src/ roots, a plugin's own folders: what the CMakeLists.txt files put on
    the include paths)."""
    folders = []
    for name, (roots, _) in LAYERS.items():
        for folder in roots:
            base = root / folder
            for directory in [base] + sorted(d for d in base.rglob("*") if d.is_dir()):
                if layer_of(root, directory / "x") == name:
                    folders.append((name, directory))
    return folders


def resolve(source, layer, quoted, header, folders):
    """The file an include names, or None for a header outside the repository (a library's). The
    including layer's own folders are searched first, as its include path has them first."""
    if quoted and (source.parent / header).is_file():
        return (source.parent / header).resolve()
    for _, folder in sorted(folders, key=lambda entry: entry[0] != layer):
        if (folder / header).is_file():
            return (folder / header).resolve()
    return None


def check_source(root, source, folders, findings):
    """Appends what `source` includes against the layers to findings; returns how many of its
    includes are the repository's own headers."""
    layer = layer_of(root, source)
    allowed = may_include(layer)
    resolved = 0
    rel = source.relative_to(root).as_posix()
    in_api = rel.startswith("plugin_api/include/")
    text = source.read_text(errors="replace")
    for match in INCLUDE.finditer(text):
        line = text.count("\n", 0, match.start()) + 1
        quoted, header = match.group(1) == '"', match.group(2)
        target = resolve(source, layer, quoted, header, folders)
        owner = layer_of(root, target) if target and root in target.parents else None
        if in_api and owner != "plugin_api" and not (owner is None and API_FOREIGN.match(header)):
            whose = f"{owner}'s ({target.relative_to(root).as_posix()})" if owner else "not the API's"
            findings.append(f"{rel}:{line}: includes \"{header}\", {whose}; the plugin API may include only "
                            "plugin_api/include, the standard library and Eigen: move what it needs into "
                            "plugin_api/include or drop the include")
        elif owner and owner not in allowed:
            findings.append(f"{rel}:{line}: includes \"{header}\" ({target.relative_to(root).as_posix()}), a "
                            f"header of {owner}, which is above {layer}; {layer} may include "
                            f"{', '.join(sorted(allowed - {layer}))}: move what it needs down or drop the include")
        resolved += owner is not None
    return resolved


def check_plugin_links(root, findings):
    for cmake in sorted((root / "plugins").rglob("CMakeLists.txt")):
        text = cmake.read_text(errors="replace")
        for match in HOST_LINK.finditer(text):
            line = text.count("\n", 0, match.start()) + 1
            findings.append(f"{cmake.relative_to(root).as_posix()}:{line}: links {match.group(0)}, a host library; "
                            "a plugin links shard::plugin_api (and shard::geometry, shard::h5) only and is "
                            "loaded by the host at run time")


def check(root):
    """Returns (findings, files checked, includes resolved inside the repository)."""
    root = root.resolve()
    folders = include_folders(root)
    findings, files, resolved = [], 0, 0
    for name, (roots, _) in LAYERS.items():
        for folder in roots:
            for source in sorted((root / folder).rglob("*")):
                if source.is_file() and source.name.endswith(SOURCE_SUFFIXES) and layer_of(root, source) == name:
                    files += 1
                    resolved += check_source(root, source, folders, findings)
    check_plugin_links(root, findings)
    return findings, files, resolved


def self_test():
    """Plants each kind of mistake in a scratch tree; every one must be reported, nothing else."""
    planted = {
        "plugin_api/include/shard/plugin.hpp": '#include <vector>\n#include "shard/simulation.hpp"\n',
        "plugin_api/include/shard/types.hpp": "#include <Eigen/Core>\n#include <fmt/format.h>\n",
        "kernel/include/shard/simulation.hpp": '#include "shard/types.hpp"\n',
        "kernel/src/run.cpp": '#include "shard/driver/run.hpp"\n',
        "driver/include/shard/driver/run.hpp": '#include "shard/simulation.hpp"\n',
        "analysis/include/shard/analysis/components.hpp": '#include "shard/simulation.hpp"\n',
        "mpi/src/labels.cpp": '#include "shard/analysis/components.hpp"\n#include "shard/driver/run.hpp"\n',
        "plugins/bond/spring/spring.cpp": '#include "shard/plugin.hpp"\n#include "shard/simulation.hpp"\n',
        "plugins/bond/spring/CMakeLists.txt": "shard_add_plugin(spring SOURCES spring.cpp LIBRARIES shard::kernel)\n",
    }
    expected = [
        r'^kernel/src/run.cpp:1: includes "shard/driver/run.hpp" .*a header of driver, which is above kernel',
        r'^mpi/src/labels.cpp:2: includes "shard/driver/run.hpp" .*a header of driver, which is above mpi',
        r'^plugin_api/include/shard/plugin.hpp:2: includes "shard/simulation.hpp", kernel\'s',
        r'^plugin_api/include/shard/types.hpp:2: includes "fmt/format.h", not the API\'s',
        r'^plugins/bond/spring/spring.cpp:2: includes "shard/simulation.hpp" .*a header of kernel, which is above plugins',
        r"^plugins/bond/spring/CMakeLists.txt:1: links shard::kernel, a host library",
    ]
    with tempfile.TemporaryDirectory() as scratch:
        root = pathlib.Path(scratch)
        for rel, text in planted.items():
            (root / rel).parent.mkdir(parents=True, exist_ok=True)
            (root / rel).write_text(text)
        findings, _, _ = check(root)
    missed = [pattern for pattern in expected if not any(re.search(pattern, f) for f in findings)]
    for finding in findings:
        print(finding)
    if missed or len(findings) != len(expected):
        print(f"self-test: {len(findings)} findings for {len(expected)} planted mistakes; not reported: {missed}")
        return 1
    print(f"self-test: all {len(expected)} planted mistakes reported")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=pathlib.Path, help="the repository to check")
    parser.add_argument("--self-test", action="store_true", help="check the checker on planted mistakes")
    args = parser.parse_args()
    if args.self_test:
        return self_test()
    if args.root is None:
        parser.error("give --root REPO or --self-test")
    findings, files, resolved = check(args.root)
    for finding in findings:
        print(finding)
    api = sorted(p.relative_to(args.root / "plugin_api/include").as_posix()
                 for p in (args.root / "plugin_api/include").rglob("*.hpp"))
    print(f"{files} files, {resolved} includes of the repository's own headers: {len(findings)} against the layers")
    print(f"plugin API ({len(api)} headers): {' '.join(api)}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
