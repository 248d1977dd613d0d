"""Layering of the C++ code (CMakeLists.txt, docs/adding_a_sensor.md): one library per folder of cpp/unexmin,
in the order core -> mapping (needs only core and OctoMap) -> hydro -> water -> geo -> sim -> raycast -> sensors (-> its
sub-folders sonar, vision, science) -> engine -> ros_layer. No folder includes a folder above it (the sub-folders of
sensors stand side by side: neither includes the other), no core folder includes a ROS header or links a ROS
library, and every project header is included with its package prefix (<unexmin/<folder>/...>) so nothing
collides with roscpp's <ros/...>.

Names follow folders: every file of cpp/unexmin/<a>/<b> declares its code in namespace unexmin::<a>::<b> (or in
namespaces nested inside it: anonymous ones, detail helpers such as vision::shading), and opens no other namespace
but forward declarations. The one root is core: cpp/unexmin/core is namespace unexmin itself (the error types
and formatNumber every library shares, as grid_map_core is namespace grid_map).

No include loops: within a library, the modules (a header and its source, foo.h with foo.cpp) include one another
without a cycle, so that each can be read, tested and replaced from the bottom up.

roscpp's internals in one place: roscpp installs headers of its managers and connections that are not its user API
(ros/topic_manager.h, ros/connection_manager.h, ros/publication.h, ...); only cpp/unexmin/ros_layer/roscpp_internals.cpp
includes them, and its header says which calls are used, why, and which roscpp versions they were checked against."""

import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
CPP = REPO / "cpp" / "unexmin"
LAYERS = [
    "core",
    "mapping",
    "hydro",
    "water",
    "geo",
    "sim",
    "raycast",
    "sensors",
    "sensors/sonar",
    "sensors/vision",
    "sensors/science",
    "engine",
    "ros_layer",
]
SIBLINGS = {"sensors/sonar", "sensors/vision", "sensors/science"}  # same rank
# First path components of headers that come from ROS (roscpp, tf2, message and service packages).
ROS_ROOTS = {
    "ros",
    "roscpp",
    "rosbag",
    "rosconsole",
    "tf",
    "tf2",
    "tf2_ros",
    "tf2_eigen",
    "image_transport",
    "kvh_1775",
    "ux1_msgs",
    "dvl_nortek",
    "std_srvs",
    "pluginlib",
    "nodelet",
    "urdf",
}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def folder_of(path):
    """The layer folder of a file under cpp/unexmin (the deepest entry of LAYERS that contains it)."""
    rel = path.relative_to(CPP).parent.as_posix()
    matches = [layer for layer in LAYERS if rel == layer or rel.startswith(layer + "/")]
    assert matches, f"{path.relative_to(REPO)} is in no library folder (expected one of {LAYERS})"
    return max(matches, key=len)


def is_ros_header(header):
    root = header.split("/")[0]
    generated = re.match(r"unexmin/[A-Z]\w*\.h$", header)  # unexmin's own messages and services
    return root in ROS_ROOTS or root.endswith("_msgs") or bool(generated)


def sources():
    files = sorted(p for p in CPP.rglob("*") if p.suffix in (".h", ".cpp"))
    assert len(files) > 40, "cpp/unexmin looks empty: the layout test would check nothing"
    return files


def includes(path):
    return INCLUDE.findall(path.read_text())


def test_every_folder_is_a_known_library():
    folders = {folder_of(p) for p in sources()}
    assert folders == set(LAYERS), f"library folders {sorted(folders)}, expected {LAYERS}"


def test_project_headers_are_included_with_the_package_prefix_and_exist():
    bad = []
    for path in sources():
        for kind, header in includes(path):
            if kind == '"':
                bad.append(f'{path.relative_to(REPO)}: #include "{header}" (use <unexmin/...>)')
            elif header.startswith("unexmin/") and not is_ros_header(header) and not (REPO / "cpp" / header).exists():
                bad.append(f"{path.relative_to(REPO)}: <{header}> does not exist")
    assert not bad, "\n".join(bad)


def test_no_folder_includes_a_folder_above_it():
    bad = []
    for path in sources():
        own = LAYERS.index(folder_of(path))
        for _, header in includes(path):
            if not header.startswith("unexmin/") or is_ros_header(header):
                continue
            other = folder_of(REPO / "cpp" / header)
            siblings = other != LAYERS[own] and {other, LAYERS[own]} <= SIBLINGS
            if LAYERS.index(other) > own or siblings:
                bad.append(f"{path.relative_to(REPO)} ({LAYERS[own]}) includes <{header}> ({other})")
    assert not bad, "\n".join(bad)


def test_the_core_includes_no_ros_header():
    bad = [
        f"{p.relative_to(REPO)}: <{h}>"
        for p in sources()
        if folder_of(p) != "ros_layer"
        for _, h in includes(p)
        if is_ros_header(h)
    ]
    assert not bad, "ROS headers in the ROS-free core:\n" + "\n".join(bad)


def libraries():
    """{folder: [linked libraries]} from the unexmin_library(...) calls of CMakeLists.txt."""
    text = (REPO / "CMakeLists.txt").read_text()
    calls = re.findall(r"^unexmin_library\(([^)]*)\)", text, re.M)
    return {c.split()[0]: c.split()[1:] for c in calls}


def test_each_library_links_only_libraries_below_it_and_only_ros_links_ros():
    libs = libraries()
    assert set(libs) == set(LAYERS) - SIBLINGS, f"libraries {sorted(libs)}"
    for folder, deps in libs.items():
        for dep in deps:
            m = re.match(r"unexmin_(\w+)$", dep)
            if m:
                assert LAYERS.index(m.group(1)) < LAYERS.index(folder), f"unexmin_{folder} links {dep}"
            if "catkin" in dep or "ros" in dep.lower() and not dep.startswith("unexmin_"):
                assert folder == "ros_layer", f"unexmin_{folder} links the ROS library {dep}"


@pytest.mark.parametrize(
    "header,expected",
    [
        ("ros/ros.h", True),
        ("sensor_msgs/Imu.h", True),
        ("unexmin/Step.h", True),
        ("unexmin/sim/world.h", False),
        ("Eigen/Core", False),
        ("embree3/rtcore.h", False),
    ],
)
def test_ros_headers_are_recognised(header, expected):
    assert is_ros_header(header) is expected


# ---------------------------------------------------------------- namespaces follow folders

ROOT_FOLDER = "core"  # its namespace is unexmin itself
NAMESPACE_OR_BRACE = re.compile(r"\b(?:inline\s+)?namespace(?:\s+([A-Za-z_]\w*(?:\s*::\s*[A-Za-z_]\w*)*))?\s*\{|[{}]")
FORWARD_DECLARATIONS = re.compile(r"^(\s*(?:class|struct)\s+[A-Za-z_]\w*\s*;)*\s*$")


def namespace_of(folder):
    """The namespace of a library folder, as a tuple of names."""
    return ("unexmin",) if folder == ROOT_FOLDER else ("unexmin",) + tuple(folder.split("/"))


def code_only(text):
    """The text without comments, string and character literals, and preprocessor lines; of each #if/#else, the
    first branch only (lanes.h opens one of two inline namespaces so)."""
    text = re.sub(
        r'//[^\n]*|/\*.*?\*/|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'',
        lambda m: re.sub(r"[^\n]", " ", m.group(0)),
        text,
        flags=re.S,
    )
    kept, skipping = [], []  # skipping: per open #if, whether its current branch is dropped
    for line in re.sub(r"\\\n", " ", text).split("\n"):
        directive = re.match(r"\s*#\s*(\w+)", line)
        if not directive:
            kept.append("" if any(skipping) else line)
            continue
        word = directive.group(1)
        if word in ("if", "ifdef", "ifndef"):
            skipping.append(False)
        elif word in ("else", "elif") and skipping:
            skipping[-1] = True
        elif word == "endif" and skipping:
            skipping.pop()
        kept.append("")
    return "\n".join(kept)


def namespace_blocks(text):
    """[(namespace, direct code)] of every namespace block of a C++ source, the file scope first as (); a
    namespace is a tuple of names ("" for an anonymous one); the direct code of a block is its text outside the
    namespace blocks it holds ("{}" stands for each other braced block)."""
    code = code_only(text)
    blocks = [((), [])]
    stack = [0]  # index into blocks of each open namespace, None for another brace
    pos = 0
    for m in NAMESPACE_OR_BRACE.finditer(code):
        inner = blocks[next(i for i in reversed(stack) if i is not None)]
        if stack[-1] is not None:
            inner[1].append(code[pos : m.start()])
        pos = m.end()
        if m.group(0).startswith(("namespace", "inline")):
            names = tuple(n.strip() for n in m.group(1).split("::")) if m.group(1) else ("",)
            path = blocks[stack[-1]][0] + names if stack[-1] is not None else None
            assert path is not None, "a namespace inside a class or function"
            blocks.append((path, []))
            stack.append(len(blocks) - 1)
        elif m.group(0) == "{":
            if stack[-1] is not None:
                inner[1].append("{}")
            stack.append(None)
        else:
            assert len(stack) > 1, "unbalanced braces"
            stack.pop()
    blocks[0][1].append(code[pos:])
    assert stack == [0], "unbalanced braces"
    return [(path, "".join(parts)) for path, parts in blocks]


def namespace_errors(name, text, expected, main=False):
    """Why the source `name` is not in namespace `expected` (a tuple), one line each; none if it is. Forward
    declarations (class X;) may stand in any namespace, the file scope included. `main`: a program's file, whose
    main() and its anonymous helpers stand at file scope; it need not open `expected`."""
    bad = []
    opened = False
    for path, code in namespace_blocks(text):
        shown = "::".join(n or "(anonymous)" for n in path)
        if main and path[:1] in ((), ("",)):
            continue
        if path == ():
            if not FORWARD_DECLARATIONS.match(code):
                bad.append(f"{name}: code at file scope (expected it in namespace {'::'.join(expected)})")
        elif path[: len(expected)] == expected:
            opened = True
        elif path == expected[: len(path)]:
            if code.strip():
                bad.append(f"{name}: code in namespace {shown}, above {'::'.join(expected)}")
        elif "" in path or not FORWARD_DECLARATIONS.match(code):
            bad.append(f"{name}: namespace {shown} (expected {'::'.join(expected)} or a namespace inside it)")
    if not opened and not main:
        bad.append(f"{name}: never opens namespace {'::'.join(expected)}")
    return bad


def test_every_file_declares_its_code_in_its_folders_namespace():
    bad = []
    for path in sources():
        expected = namespace_of(folder_of(path))
        bad += namespace_errors(
            path.relative_to(REPO).as_posix(), path.read_text(), expected, main=path.name.endswith("_main.cpp")
        )
    assert not bad, "namespaces that do not follow folders:\n" + "\n".join(bad)


SONAR = ("unexmin", "sensors", "sonar")


@pytest.mark.parametrize(
    "text,errors",
    [
        ("namespace unexmin {\nnamespace sensors {\nnamespace sonar {\nclass M3 {};\n}\n}\n}\n", 0),
        ("namespace unexmin::sensors::sonar {\nnamespace {\nint f() { return 1; }\n}\n}\n", 0),
        ("namespace unexmin {\nnamespace sim {\nclass World;\n}\nnamespace sensors::sonar {\nstruct A {};\n}\n}\n", 0),
        (
            "namespace unexmin {\nnamespace sensors {\nnamespace sonar {\n#if X\ninline namespace a {\n#else\n"
            "inline namespace b {\n#endif\nint g(char c = '{') { return \"}\"[0]; }  // {\n}\n}\n}\n}\n",
            0,
        ),
        ("namespace unexmin {\nnamespace sonar {\nclass M3 {};\n}\n}\n", 2),  # the folder's old namespace
        ("namespace unexmin {\nnamespace sensors {\nclass M3 {};\n}\n}\n", 2),  # the parent folder's
        ("namespace unexmin {\nnamespace sensors {\nint x;\nnamespace sonar {\n}\n}\n}\n", 1),  # code above it
        ("namespace unexmin {\nnamespace sim {\nclass World { int x; };\n}\nnamespace sensors::sonar {\n}\n}\n", 1),
        ("class M3 {};\nnamespace unexmin::sensors::sonar {\n}\n", 1),  # code at file scope
        ("namespace {\nint f();\n}\nnamespace unexmin::sensors::sonar {\n}\n", 1),  # anonymous, outside it
        ("class btRigidBody;\nnamespace unexmin::sensors::sonar {\n}\n", 0),  # forward declaration
    ],
)
def test_the_namespace_check_tells_right_from_wrong(text, errors):
    assert len(namespace_errors("x.h", text, SONAR)) == errors, namespace_errors("x.h", text, SONAR)


def test_a_programs_main_may_stand_at_file_scope_but_its_namespaces_follow_the_folder():
    text = "namespace {\nvoid stop(int) {}\n}\nint main() { return 0; }\n"
    assert namespace_errors("x_main.cpp", text, SONAR, main=True) == []
    assert len(namespace_errors("x_main.cpp", text, SONAR)) == 3
    assert len(namespace_errors("x_main.cpp", "namespace unexmin::sonar {\nint x;\n}\n", SONAR, main=True)) == 1


def test_the_core_is_the_root_namespace_and_every_other_folder_its_path():
    assert namespace_of("core") == ("unexmin",)
    assert namespace_of("sensors/sonar") == SONAR
    assert namespace_of("ros_layer") == ("unexmin", "ros_layer")


# Libraries of ROS 1 (roscpp and what it brings, tf2, rosbag) as ldd names them.
ROS_LIBRARY = re.compile(r"lib(roscpp|rosconsole|rosbag|rostime|cpp_common|xmlrpcpp|roslib|tf2|message_filters)\w*\.so")


def test_the_python_module_includes_no_ros_header():
    files = sorted((REPO / "cpp" / "python").glob("*.[ch]*"))
    assert files, "cpp/python looks empty"
    bad = [f"{p.relative_to(REPO)}: <{h}>" for p in files for _, h in includes(p) if is_ros_header(h)]
    assert not bad, "ROS headers in the Python module:\n" + "\n".join(bad)


def test_the_python_module_links_no_ros_library():
    import subprocess

    from unexmin import _core

    out = subprocess.run(["ldd", _core.__file__], capture_output=True, text=True, check=True).stdout
    assert "libunexmin_engine" in out or "libBullet" in out, f"ldd of {_core.__file__} lists nothing of ours:\n{out}"
    ros = sorted({m.group(0) for m in ROS_LIBRARY.finditer(out)})
    assert not ros, f"{_core.__file__} links ROS libraries {ros}:\n{out}"


def test_the_ros_library_pattern_tells_ros_from_the_rest():
    assert ROS_LIBRARY.search("libroscpp.so.1d => /usr/lib/x86_64-linux-gnu/libroscpp.so.1d")
    assert ROS_LIBRARY.search("librosbag_storage.so.1d => /usr/lib/librosbag_storage.so.1d")
    assert not ROS_LIBRARY.search("libBulletDynamics.so.3.24 => /usr/lib/libBulletDynamics.so.3.24")
    assert not ROS_LIBRARY.search("libunexmin_engine.so => /ws/devel/lib/libunexmin_engine.so")


# ---------------------------------------------------------------- no include loops within a library

PROJECT_INCLUDE = re.compile(r"^\s*#\s*include\s*<(unexmin/[^>]+)>", re.M)


def module_of(path):
    """The module of a file under cpp/: its path without the suffix (foo.h and foo.cpp are one module)."""
    return path.relative_to(REPO / "cpp").with_suffix("").as_posix()


def library_of(path):
    """The library a file under cpp/ belongs to: its layer folder, or "python" for the module under cpp/python."""
    return "python" if path.is_relative_to(REPO / "cpp" / "python") else folder_of(path)


def module_graph():
    """{module: {included module: (file that includes it, header)}} over the #include <unexmin/...> lines of cpp/,
    an edge only between two modules of the same library."""
    files = sources() + sorted((REPO / "cpp" / "python").glob("*.[ch]*"))
    graph = {}
    for path in files:
        source = module_of(path)
        for header in PROJECT_INCLUDE.findall(path.read_text()):
            target = REPO / "cpp" / header
            if is_ros_header(header) or not target.exists() or module_of(target) == source:
                continue
            if library_of(target) == library_of(path):
                graph.setdefault(source, {})[module_of(target)] = (path.relative_to(REPO).as_posix(), header)
    return graph


def include_cycles(graph):
    """The cycles of `graph` ({node: {successor: label}}), one per strongly connected component of two or more
    nodes, each as the list of its nodes in order (the first again at the end)."""
    index, low, stack, on_stack, components = {}, {}, [], set(), []

    def connect(v):  # Tarjan's algorithm
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, {})):
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.add(w)
                if w == v:
                    break
            if len(component) > 1:
                components.append(component)

    for v in sorted(set(graph) | {w for succ in graph.values() for w in succ}):
        if v not in index:
            connect(v)
    return [cycle_through(min(c), c, graph) for c in components]


def cycle_through(start, component, graph):
    """A shortest cycle from `start` back to it inside `component` (breadth first), as a list of nodes."""
    previous, frontier = {}, [start]
    while frontier:
        following = []
        for v in frontier:
            for w in sorted(graph.get(v, {})):
                if w == start:
                    path = [v]
                    while path[-1] != start:
                        path.append(previous[path[-1]])
                    return path[::-1] + [start]
                if w in component and w not in previous:
                    previous[w] = v
                    following.append(w)
        frontier = following
    raise AssertionError(f"no cycle through {start} in {sorted(component)}")


def describe_cycle(cycle, graph):
    return (
        " -> ".join(cycle)
        + "\n"
        + "\n".join(f"    {graph[a][b][0]} includes <{graph[a][b][1]}>" for a, b in zip(cycle, cycle[1:]))
    )


def test_no_include_loop_within_a_library():
    graph = module_graph()
    assert sum(len(v) for v in graph.values()) > 50, "the include graph looks empty: the check would check nothing"
    cycles = include_cycles(graph)
    assert not cycles, "include loops (a module is a header with its source):\n" + "\n".join(
        describe_cycle(c, graph) for c in cycles
    )


@pytest.mark.parametrize(
    "graph,loops",
    [
        ({"a": {"b": 0}, "b": {"c": 0}}, []),
        ({"a": {"b": 0, "c": 0}, "b": {"c": 0}}, []),
        ({"a": {"b": 0}, "b": {"a": 0}}, [["a", "b", "a"]]),
        ({"r": {"w": 0}, "w": {"s": 0}, "s": {"r": 0}, "x": {"r": 0}}, [["r", "w", "s", "r"]]),
        (
            {"a": {"b": 0}, "b": {"a": 0}, "c": {"d": 0}, "d": {"e": 0}, "e": {"c": 0}},
            [["a", "b", "a"], ["c", "d", "e", "c"]],
        ),
    ],
)
def test_the_loop_finder_tells_loops_from_layers(graph, loops):
    assert sorted(include_cycles(graph)) == loops


# ---------------------------------------------------------------- roscpp's internals in one file

# roscpp's installed headers that are not its user API: its managers, connections and links.
ROSCPP_INTERNALS = {
    f"ros/{name}.h"
    for name in (
        "topic_manager",
        "connection_manager",
        "poll_manager",
        "poll_set",
        "publication",
        "subscription",
        "subscription_queue",
        "service_manager",
        "service_publication",
        "service_client_link",
        "service_server_link",
        "xmlrpc_manager",
        "connection",
        "publisher_link",
        "subscriber_link",
        "transport_publisher_link",
        "transport_subscriber_link",
        "intraprocess_publisher_link",
        "intraprocess_subscriber_link",
        "internal_timer_manager",
        "timer_manager",
    )
}
ROSCPP_INTERNALS_FILES = {"cpp/unexmin/ros_layer/roscpp_internals.h", "cpp/unexmin/ros_layer/roscpp_internals.cpp"}


def is_roscpp_internal(header):
    return header in ROSCPP_INTERNALS or header.startswith("ros/transport/")


def test_only_roscpp_internals_includes_roscpps_internal_headers():
    files = sorted(p for folder in ("cpp", "test", "bench", "docs/tools") for p in (REPO / folder).rglob("*.[ch]*"))
    assert all((REPO / f).exists() for f in ROSCPP_INTERNALS_FILES), f"{sorted(ROSCPP_INTERNALS_FILES)} are missing"
    bad = [
        f"{p.relative_to(REPO)}: <{h}>"
        for p in files
        if p.suffix in (".h", ".cpp") and p.relative_to(REPO).as_posix() not in ROSCPP_INTERNALS_FILES
        for _, h in includes(p)
        if is_roscpp_internal(h)
    ]
    assert not bad, "roscpp internals outside ros_layer/roscpp_internals.{h,cpp} (add a function there):\n" + "\n".join(
        bad
    )


def test_roscpp_internals_says_what_it_uses_and_the_versions_checked():
    header = (REPO / "cpp/unexmin/ros_layer/roscpp_internals.h").read_text()
    comment = header[: header.index("#pragma once")]
    used = sorted(
        {h for _, h in includes(REPO / "cpp/unexmin/ros_layer/roscpp_internals.cpp") if is_roscpp_internal(h)}
    )
    assert used, "roscpp_internals.cpp includes no roscpp internal header"
    for h in used:
        manager = "".join(part.capitalize() for part in Path(h).stem.split("_"))
        assert f"ros::{manager}" in comment, f"roscpp_internals.h's comment does not say what of <{h}> it uses"
    assert re.search(r"roscpp 1\.\d+\.\d+", comment), "roscpp_internals.h's comment names no roscpp version"
