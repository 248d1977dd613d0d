"""Every repository path a comment names exists: a reader who follows a comment to a file finds the file.

Comments read: C++ `//` and `/* */` comments (.h, .cpp, .c); Python `#` comments and docstrings (module, class and
function docstrings of .py files and of the extensionless Python scripts in nodes/); `#` comments of CMake, shell,
YAML (config/, worlds/*.world, .rviz), msg, srv and TOML files; `<!-- -->` comments of XML (.launch, .xacro, .test,
.xml). A file is read when git tracks it (outside a git checkout, every file of the tree).

A word of a comment (what lies between blanks, quotes, brackets, commas and semicolons) names a repository path when
- it holds a `/` and either its first component is a folder tracked at the top of the repository (cpp/, python/,
  docs/, test/, launch/, ...), a library folder of cpp/unexmin (core/, hydro/, ros_layer/, ...) or a package of
  python/unexmin (missions/, scripting/, ...), or it ends in a suffix of the repository's own sources (.h, .cpp,
  .py, .md, .launch, .xacro, .test, .world), so that a source named in a folder that does not exist (`gone/...`)
  is read; `unexmin/` (the include and import prefix) counts when a library, a package or a file name follows it
  (`unexmin/sim/robot.h`), not before a type or an id (`unexmin/Dvl`, `unexmin/_core`, `unexmin/StationKeeping-v0`);
- it is not a URL (`://`), an absolute path (`/usr/...`, a topic `/ux1/dvl`) or a pattern: a word with `<`, `>`,
  `*`, `{`, `}`, `$`, `%`, `|`, `=`, `@` or `...` (`<family>_sensor.h`, `worlds/*.world`, `$(find unexmin)/x`)
  is a placeholder and is skipped, and so is a source under a folder in capitals (`OUT/NAME.world`, `M/x.ply`).
Trailing punctuation (`.,;:`), a `:<line>` suffix and a `#anchor` are dropped first.

It exists when the file (or, for a word ending in `/`, the folder) is found relative to one of: the repository
root, the commenting file's folder, cpp/ (`unexmin/sim/robot.h`), cpp/unexmin/ (`sim/robot.h`), python/
(`unexmin/bag.py`) or python/unexmin/ (`missions/explore/plan.py`). A program is found by its source
(`bench/camera_fps` is built from bench/camera_fps.cpp). A header the system's /usr/include holds
(`linux/joystick.h`, `octomap/OcTree.h`) is another library's. A path under a folder the repository's .gitignore
anchors at its root (`/build/`, `/devel/`, `/mission_output/`, `/worlds/meshes/mine/`) is generated and accepted
without a look.

Not read: words whose first component names no folder of the repository and that end in none of those suffixes
(`sensor_msgs/Image`, `dvl_nortek/DvlBottomWaterTrack`: other packages' names) and bare file names (no `/`)."""

import ast
import io
import re
import subprocess
import tokenize
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]

CPP_SUFFIXES = {".h", ".cpp", ".c"}
HASH_SUFFIXES = {".cmake", ".sh", ".yaml", ".yml", ".world", ".msg", ".srv", ".toml", ".rviz"}
HASH_NAMES = {"CMakeLists.txt"}
XML_SUFFIXES = {".launch", ".xacro", ".test", ".xml", ".urdf"}
PLACEHOLDER_FOLDER = re.compile(r"[A-Z][A-Z0-9_]*$")  # OUT/, DIR/, M/: a folder the reader names
PLACEHOLDER = re.compile(r"[<>*{}$%|=@]|\.\.\.|…")
OWN_SUFFIXES = {".h", ".cpp", ".py", ".md", ".launch", ".xacro", ".test", ".world"}
SYSTEM_INCLUDE = Path("/usr/include")
PROGRAM_SOURCES = (".cpp", ".py")
# a word: what lies between blanks, quotes, brackets and separators a path holds none of
WORD = re.compile(r"[^\s\"'`()\[\],;]+")


def tracked_files():
    """The files of the repository, relative to its root (git's list when there is one)."""
    try:
        out = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True, check=True).stdout
        files = [Path(line) for line in out.splitlines() if line]
    except (OSError, subprocess.CalledProcessError):
        files = [p.relative_to(REPO) for p in REPO.rglob("*") if p.is_file() and ".git" not in p.parts]
    assert len(files) > 200, "the repository looks empty: the test would check nothing"
    return [f for f in files if (REPO / f).is_file()]


def generated_roots():
    """Folders the .gitignore anchors at the repository root: what the build and the tools write."""
    roots = []
    for line in (REPO / ".gitignore").read_text().splitlines():
        line = line.strip()
        if line.startswith("/") and not PLACEHOLDER.search(line):
            roots.append(line.strip("/"))
    return roots


def search_bases():
    return [Path("."), Path("cpp"), Path("cpp/unexmin"), Path("python"), Path("python/unexmin")]


def path_roots(files):
    """First components that make a word a repository path (the folders at the top of the repository, the library
    folders of cpp/unexmin and the packages of python/unexmin), and the names that may follow `unexmin/`."""
    top = {f.parts[0] for f in files if len(f.parts) > 1}
    libraries = {p.name for p in (REPO / "cpp" / "unexmin").iterdir() if p.is_dir()}
    packages = {p.name for p in (REPO / "python" / "unexmin").iterdir() if (p / "__init__.py").is_file()}
    return top | libraries | packages, libraries | packages


def script_kind(path):
    """'python' or 'shell' for an extensionless script (by its #! line), else None."""
    try:
        first = path.open(encoding="utf-8", errors="replace").readline()
    except OSError:
        return None
    if first.startswith("#!") and "python" in first:
        return "python"
    if first.startswith("#!") and ("sh" in first.split("/")[-1] or "bash" in first):
        return "shell"
    return None


def cpp_comments(text):
    """(line, text) of every // and /* */ comment, string and character literals skipped."""
    out, i, line, n = [], 0, 1, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end < 0 else end
            out.append((line, text[i + 2 : end]))
            i = end
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end
            for k, part in enumerate(text[i + 2 : end].split("\n")):
                out.append((line + k, part))
            line += text.count("\n", i, end)
            i = end + 2
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            open_paren = text.find("(", i + 2)
            delim = text[i + 2 : open_paren]
            end = text.find(")" + delim + '"', open_paren)
            end = n if end < 0 else end + len(delim) + 2
            line += text.count("\n", i, end)
            i = end
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # a digit separator (1'000)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            i = j + 1
        else:
            i += 1
    return out


def python_comments(text):
    """(line, text) of every # comment and every line of the module's, classes' and functions' docstrings."""
    out = []
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type == tokenize.COMMENT and not (tok.start[0] == 1 and tok.string.startswith("#!")):
            out.append((tok.start[0], tok.string[1:]))
    tree = ast.parse(text)
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                if isinstance(first.value.value, str):
                    for k, part in enumerate(first.value.value.split("\n")):
                        out.append((first.lineno + k, part))
    return out


def hash_comments(text):
    """(line, text) of every # comment of a CMake, shell or YAML file: a # that starts the line or follows a blank,
    outside quotes (shell's $# and ${#x} are no comments)."""
    out = []
    for number, line in enumerate(text.splitlines(), 1):
        if number == 1 and line.startswith("#!"):
            continue
        quote = None
        for k, c in enumerate(line):
            if quote:
                quote = None if c == quote else quote
            elif c in "\"'":
                quote = c
            elif c == "#" and (k == 0 or line[k - 1] in " \t"):
                out.append((number, line[k + 1 :]))
                break
    return out


def xml_comments(text):
    out = []
    for m in re.finditer(r"<!--(.*?)-->", text, re.S):
        line = text.count("\n", 0, m.start()) + 1
        for k, part in enumerate(m.group(1).split("\n")):
            out.append((line + k, part))
    return out


def comments(rel):
    """(line, text) of the comments of one repository file, or [] for a file of no kind read here."""
    path = REPO / rel
    suffix, kind = path.suffix, None
    if suffix in CPP_SUFFIXES:
        kind = cpp_comments
    elif suffix == ".py":
        kind = python_comments
    elif suffix in HASH_SUFFIXES or path.name in HASH_NAMES:
        kind = hash_comments
    elif suffix in XML_SUFFIXES:
        kind = xml_comments
    elif suffix == "":
        kind = {"python": python_comments, "shell": hash_comments}.get(script_kind(path))
    if kind is None:
        return []
    return kind(path.read_text(encoding="utf-8", errors="replace"))


def path_words(text, roots, folders):
    """The words of one comment line that name a repository path (the module docstring's rules)."""
    for m in WORD.finditer(text):
        word = m.group(0)
        if "/" not in word or "://" in word or word.startswith("/") or PLACEHOLDER.search(word):
            continue
        word = re.sub(r"#.*$", "", word)
        word = re.sub(r":\d+(-\d+)?$", "", word.rstrip(".,;:"))
        word = word.rstrip(".,;:")
        parts = word.rstrip("/").split("/")
        if len(parts) < 2:
            continue
        if parts[0] == "unexmin" and (parts[1] in folders or "." in parts[1]):
            yield word
        elif parts[0] in roots:
            yield word
        elif Path(parts[-1]).suffix in OWN_SUFFIXES and not PLACEHOLDER_FOLDER.match(parts[0]):
            yield word


def exists(word, rel, generated):
    if any(word == g or word.startswith(g + "/") for g in generated):
        return True
    bases = [rel.parent, *search_bases()]
    if word.endswith(".h") and (SYSTEM_INCLUDE / word).is_file():  # another library's header
        return True
    if word.endswith("/"):  # a folder
        return any((REPO / base / word).is_dir() for base in bases)
    candidates = [word, *(word + suffix for suffix in PROGRAM_SOURCES)]
    return any((REPO / base / c).exists() for base in bases for c in candidates)


def stale_paths():
    files = tracked_files()
    (roots, folders), generated = path_roots(files), generated_roots()
    stale, seen = [], 0
    for rel in files:
        for line, text in comments(rel):
            for word in path_words(text, roots, folders):
                seen += 1
                if not exists(word, rel, generated):
                    stale.append(f"{rel}:{line}: {word}")
    return stale, seen


def test_every_path_a_comment_names_exists():
    stale, seen = stale_paths()
    assert seen > 300, f"only {seen} paths found in comments: the reader is broken"
    assert not stale, "comments name paths that do not exist:\n" + "\n".join(stale)


def test_the_reader_finds_each_kind_of_comment():
    """The reader sees every kind of comment and nothing else: string literals, digit separators, $# and ${#x}."""
    cpp = cpp_comments('int a = 1\'000; const char* s = "// docs/not_a_comment.md";  // docs/a.md\n/* sim/b.h */\n')
    assert cpp == [(1, " docs/a.md"), (2, " sim/b.h ")]
    raw = cpp_comments('auto x = R"(// docs/raw.md\n)";\n// docs/after.md\n')
    assert raw == [(3, " docs/after.md")]
    py = python_comments(
        '"""Module: docs/m.md."""\n\n\ndef f():\n    """docs/f.md"""\n    x = "docs/s.md"  # docs/c.md\n'
    )
    assert sorted(py) == [(1, "Module: docs/m.md."), (5, "docs/f.md"), (6, " docs/c.md")]
    sh = hash_comments('#!/bin/bash\necho "$#" ${#x} "a # b"  # docs/sh.md\n# cpp/x.h\n')
    assert sh == [(2, " docs/sh.md"), (3, " cpp/x.h")]
    xml = xml_comments("<a>\n<!-- one\n docs/x.md -->\n</a>\n")
    assert xml == [(2, " one"), (3, " docs/x.md ")]


def test_the_reader_tells_a_path_from_other_words():
    words = path_words(
        "see docs/a.md:12, (sim/robot.h) https://x.org/docs/y.md /ux1/dvl cpp/<family>_sensor.h docs/*.md"
        " sensor_msgs/Image octomap/OcTree.h ros/gone.cpp docs/b.md#anchor sim/ unexmin/Dvl unexmin/sim/x.h"
        " OUT/NAME.world",
        roots={"cpp", "docs", "sim"},
        folders={"sim"},
    )
    assert list(words) == [
        "docs/a.md",
        "sim/robot.h",
        "octomap/OcTree.h",
        "ros/gone.cpp",
        "docs/b.md",
        "unexmin/sim/x.h",
    ]


def test_a_missing_path_is_reported():
    generated = generated_roots()
    here = Path("test/pytest/test_comment_paths.py")
    assert exists("test/pytest/test_layout.py", here, generated)
    assert exists("conftest.py/", here, generated) is False  # a file is no folder
    assert exists("sim/robot.h", here, generated)
    assert exists("unexmin/sim/robot.h", here, generated)
    assert exists("missions/explore/plan.py", here, generated)
    assert exists("bench/camera_fps", here, generated)
    assert exists("devel/lib/unexmin/simulator_node", here, generated)
    assert exists("linux/joystick.h", here, generated)
    assert not exists("ros/sensor_families.cpp", here, generated)
    assert not exists("docs/no_such_page.md", here, generated)
    assert not exists("bench/no_such_program", here, generated)
