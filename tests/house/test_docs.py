"""The documentation as a reader meets it: README.md, BENCHMARKS.md and every docs/*.md.

Proved here, from the files alone (no server, no browser, nothing run):

- every relative Markdown link and image resolves to a file or directory of the repository, relative
  to the file that holds it, and every ``#anchor`` to a heading of its target Markdown file (GitHub's
  slugs: lower case, spaces to ``-``, punctuation dropped, ``-1``, ``-2`` for a repeated heading);
- every command in a ``bash``, ``sh``, ``shell`` or ``console`` block names what exists: a Makefile
  target, a script, a module (the repository's or an installed one), a Dockerfile or compose file, a
  manifest, a test file; a command of any other kind is in ``ALLOWED``, with the reason, so that a new
  kind of command in the docs is a visible decision;
- README.md stays within 250 lines, with ``make run`` and ``make test`` as its quick start, and
  BENCHMARKS.md within 400 (the older rounds live in docs/benchmarks-log.md).

A positive control runs the same functions on a small text with a broken link, a missing anchor, an
unknown make target, a missing script and an unlisted command, and requires each to be reported.
"""
from __future__ import annotations

import functools
import importlib.util
import re
import shlex
import unicodedata
from pathlib import Path
from urllib.parse import unquote

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = [ROOT / "README.md", ROOT / "BENCHMARKS.md", *sorted((ROOT / "docs").glob("*.md"))]
LONGEST = {"README.md": 250, "BENCHMARKS.md": 400}
SHELL_LANGUAGES = {"bash", "sh", "shell", "console"}

# Commands that name nothing in the repository this test could look up. Each is a decision: a new
# kind of command in the docs fails here until it is listed (with why it needs no check) or given a
# check in ``command_problems``.
ALLOWED = {
    "apt-get": "installs Debian's packages (chromium, postgresql, poppler-utils, TeX Live)",
    "curl": "asks a running server",
    "echo": "writes a line (the admin's env file)",
    "git": "the repository's own history",
    "issues": "the project's issue tracker",
    "openssl": "makes the secrets",
    "printf": "writes the admin's env file",
    "umask": "keeps the env file private",
}
# Words that run the command after them: ``sudo make run`` is checked as ``make run``.
WRAPPERS = {"sudo", "env", "time", "nohup", "flock"}
SEPARATORS = {"&&", "||", ";", ";;", "|", "|&", "&", "(", ")"}
PYTHON = re.compile(r"python(3(\.\d+)*)?")


# ---------------------------------------------------------------- reading Markdown

_FENCE = re.compile(r"^[ \t]*(`{3,}|~{3,})[ \t]*([^\s`]*)")


def fenced_blocks(text: str) -> list[tuple[str, int, list[str]]]:
    """Each fenced code block of ``text``: its language (lower case, "" if none), the line number of
    its first line of code, and its lines. An unclosed fence runs to the end, as on GitHub."""
    blocks, lines, i = [], text.split("\n"), 0
    while i < len(lines):
        opening = _FENCE.match(lines[i])
        if not opening:
            i += 1
            continue
        fence, language = opening.group(1), opening.group(2).lower()
        body, i = [], i + 1
        start = i + 1
        while i < len(lines) and not re.match(rf"^[ \t]*{fence[0]}{{{len(fence)},}}[ \t]*$", lines[i]):
            body.append(lines[i])
            i += 1
        blocks.append((language, start, body))
        i += 1
    return blocks


def prose(text: str, code_spans: bool = True) -> str:
    """``text`` with its fenced blocks and (unless ``code_spans`` is False) its inline code spans
    blanked out, newlines kept so that offsets still give line numbers: where links are links."""
    lines, in_fence = text.split("\n"), None
    for n, line in enumerate(lines):
        opening = _FENCE.match(line)
        if in_fence is None and opening:
            in_fence, lines[n] = opening.group(1), ""
        elif in_fence is not None:
            if re.match(rf"^[ \t]*{in_fence[0]}{{{len(in_fence)},}}[ \t]*$", line):
                in_fence = None
            lines[n] = ""
    blanked = "\n".join(lines)
    if not code_spans:
        return blanked
    span = re.compile(r"(?<!`)(`+)(?!`)((?:(?!\n[ \t]*\n).)+?)(?<!`)\1(?!`)", re.DOTALL)
    return span.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), blanked)


_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^)\s>]*)>?(?:\s+(?:\"[^\"]*\"|'[^']*'))?\s*\)")
_DEFINITION = re.compile(r"^ {0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s|$)", re.MULTILINE)


def links(text: str) -> list[tuple[int, str]]:
    """(line number, target) of every inline link, image and link definition outside code."""
    body = prose(text)
    found = [(m.start(1), m.group(1)) for pattern in (_LINK, _DEFINITION) for m in pattern.finditer(body)]
    return sorted((body.count("\n", 0, at) + 1, target) for at, target in found)


def github_slug(heading: str) -> str:
    """The anchor GitHub gives a heading's text: its rendered text in lower case, every character but
    letters, marks, digits, connector punctuation (``_``), spaces and hyphens dropped, and each space
    made a hyphen (so "Inside the LMS (LTI 1.3)" is ``inside-the-lms-lti-13``)."""
    rendered = re.sub(r"!?\[((?:[^\[\]]|\[[^\[\]]*\])*)\]\([^)]*\)", r"\1", heading)  # a link: its text
    rendered = rendered.replace("`", "")
    kept = (ch for ch in rendered.strip().lower()
            if ch in " -" or unicodedata.category(ch)[0] in "LMN" or unicodedata.category(ch) == "Pc")
    return "".join(kept).replace(" ", "-")


def heading_anchors(text: str) -> set[str]:
    """Every anchor the headings of ``text`` get on GitHub, a repeated one numbered as GitHub numbers
    it (the second "Setup" is ``setup-1``); headings inside fenced code are not headings."""
    anchors, seen = set(), {}
    for line in prose(text, code_spans=False).split("\n"):
        m = re.match(r"^ {0,3}#{1,6}(?:[ \t]+(.*?))?[ \t]*$", line)
        if not m:
            continue
        base = slug = github_slug(re.sub(r"[ \t]+#+$", "", m.group(1) or ""))
        while slug in seen:
            seen[base] += 1
            slug = f"{base}-{seen[base]}"
        seen[slug] = 0
        anchors.add(slug)
    return anchors


def broken_links(doc: Path, text: str, root: Path = ROOT) -> list[str]:
    """What is wrong with each relative link of ``text`` (the content of ``doc``): a target that is
    not a file or directory of the repository, relative to ``doc``'s folder, or an ``#anchor`` that is
    no heading of its Markdown target. Links with a scheme (https:, mailto:) are not followed."""
    problems = []
    for line, target in links(text):
        if not target or re.match(r"[A-Za-z][A-Za-z0-9+.-]*:|//", target):
            continue
        path_part, _, anchor = target.partition("#")
        where = f"{doc.name}:{line}: ({target})"
        resolved = (doc.parent / unquote(path_part)).resolve() if path_part else doc
        if path_part:
            if not resolved.is_relative_to(root):
                problems.append(f"{where} points outside the repository")
                continue
            if not resolved.exists():
                problems.append(f"{where}: no such file or directory")
                continue
        if not anchor:
            continue
        if resolved.suffix.lower() == ".md":
            target_text = text if resolved == doc else resolved.read_text(encoding="utf-8")
            if unquote(anchor).lower() not in heading_anchors(target_text):
                problems.append(f"{where}: no heading with the anchor #{anchor} in {resolved.name}")
        elif not re.fullmatch(r"L\d+(-L\d+)?", anchor):
            problems.append(f"{where}: #{anchor} in a file that is not Markdown")
    return problems


# ---------------------------------------------------------------- reading shell commands

def shell_commands(text: str) -> list[tuple[int, str]]:
    """(line number, command line) of each command in the bash/sh/shell/console blocks of ``text``: a
    leading ``$ `` stripped, a line ending in a backslash joined with the next, comment lines left
    out, and in a console block only the ``$ `` lines (the rest is output)."""
    commands = []
    for language, first, body in fenced_blocks(text):
        if language not in SHELL_LANGUAGES:
            continue
        pending, start = "", first
        for offset, raw in enumerate(body):
            line = raw.rstrip()
            if not pending:
                line = line.strip()
                if language == "console" and not line.startswith("$ "):
                    continue
                line = line[2:] if line.startswith("$ ") else line
                if not line or line.startswith("#"):
                    continue
                start = first + offset
            if line.endswith("\\"):
                pending += line[:-1] + " "
                continue
            commands.append((start, pending + line))
            pending = ""
        if pending:
            commands.append((start, pending))
    return commands


def _without_comment(line: str) -> str:
    """The line up to a ``#`` that starts a word outside quotes (the shell's comment)."""
    quote = None
    for i, ch in enumerate(line):
        if quote:
            quote = None if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch == "#" and (i == 0 or line[i - 1].isspace()):
            return line[:i]
    return line


def _substitutions(line: str) -> tuple[str, list[str]]:
    """The line with each ``$(…)`` and backquoted command replaced by a placeholder word, and the
    commands they held (checked as commands of their own)."""
    inner, out, i, single, double = [], [], 0, False, False
    while i < len(line):
        ch = line[i]
        if ch == "'" and not double:
            single = not single
        elif ch == '"' and not single:
            double = not double
        if not single and line.startswith("$(", i):
            depth, j = 1, i + 2
            while j < len(line) and depth:
                depth += {"(": 1, ")": -1}.get(line[j], 0)
                j += 1
            inner.append(line[i + 2:j - 1])
            out.append("SUBSTITUTED")
            i = j
            continue
        if not single and ch == "`":
            j = line.find("`", i + 1)
            j = len(line) if j < 0 else j
            inner.append(line[i + 1:j])
            out.append("SUBSTITUTED")
            i = j + 1
            continue
        out.append(ch)
        i += 1
    return "".join(out), inner


def simple_commands(command_line: str) -> list[list[str]]:
    """The simple commands of one command line, each as its words, as the shell would split it: at
    ``&&``, ``||``, ``;``, ``|``, ``&`` and a subshell's brackets; without redirections (``> file``),
    the ``VAR=value`` assignments before a command, a wrapper (``sudo``, ``env``, ``flock LOCK``)
    or a comment; a command substitution's command as one more command."""
    line, inner = _substitutions(_without_comment(command_line))
    lexer = shlex.shlex(line, posix=True, punctuation_chars=";&|()<>")
    lexer.whitespace_split, lexer.commenters = True, ""
    segments, current, skip_next = [], [], False
    for token in lexer:
        if skip_next:
            skip_next = False
        elif token in SEPARATORS:
            segments.append(current)
            current = []
        elif token and set(token) <= set("<>&|") and ("<" in token or ">" in token):
            skip_next = True  # a redirection's target
        else:
            current.append(token)
    segments.append(current)
    commands = []
    for words in segments:
        while words and re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*=.*", words[0]):
            words = words[1:]
        while words and words[0] in WRAPPERS:
            wrapper, words = words[0], words[1:]
            while words and (words[0].startswith("-") or "=" in words[0]):
                words = words[1:]
            if wrapper == "flock" and words:
                words = words[1:]  # the lock file
        if words:
            commands.append(words)
    for command in inner:
        commands += simple_commands(command)
    return commands


# ---------------------------------------------------------------- what a command names

@functools.cache
def make_targets(root: Path = ROOT) -> frozenset[str]:
    """The targets the Makefile defines (rule lines ``target …: …``, not ``VAR := …``)."""
    targets = set()
    for line in (root / "Makefile").read_text(encoding="utf-8").split("\n"):
        m = re.match(r"^([^\s#][^:=]*?)\s*::?(?!=)", line)
        if m:
            targets |= set(m.group(1).split())
    return frozenset(targets)


def _missing(path: str, root: Path, what: str) -> list[str]:
    if Path(path).is_absolute():
        return [f"{what} {path} is not in the repository"]
    resolved = (root / path).resolve()
    if not resolved.is_relative_to(root) or not resolved.exists():
        return [f"{what} {path} does not exist"]
    return []


def _module_missing(module: str, root: Path) -> list[str]:
    as_path = root / module.replace(".", "/")
    if as_path.with_suffix(".py").is_file() or (as_path / "__init__.py").is_file() \
            or (as_path / "__main__.py").is_file():
        return []
    try:
        if importlib.util.find_spec(module) is not None:
            return []
    except (ImportError, ValueError):
        pass
    return [f"module {module} is neither the repository's nor installed"]


def _values_after(args: list[str], *options: str) -> list[str]:
    """The values given to ``options`` in ``args`` (``-f X``, ``--file X``, ``--file=X``)."""
    values = []
    for i, arg in enumerate(args):
        if arg in options and i + 1 < len(args):
            values.append(args[i + 1])
        values += [arg.split("=", 1)[1] for option in options
                   if option.startswith("--") and arg.startswith(option + "=")]
    return values


def _pytest_missing(args: list[str], root: Path) -> list[str]:
    paths = [arg.split("::")[0] for arg in args if not arg.startswith("-")]
    return [problem for path in paths if path.endswith(".py") or "/" in path
            for problem in _missing(path, root, "test file")]


def _python_missing(args: list[str], root: Path) -> list[str]:
    i = 0
    while i < len(args):
        arg = args[i]
        if arg == "-m":
            if i + 1 == len(args):
                return ["python -m without a module"]
            module, rest = args[i + 1], args[i + 2:]
            return _module_missing(module, root) + (_pytest_missing(rest, root) if module == "pytest" else [])
        if arg == "-c":
            return []
        if arg in ("-X", "-W"):
            i += 2
        elif arg.startswith("-"):
            i += 1
        else:
            return _missing(arg, root, "script")
    return []


DOCKER_VALUE_OPTIONS = {"-t", "--tag", "-f", "--file", "--build-arg", "--target", "--platform", "--label",
                        "--secret", "--network", "--progress", "--cache-from", "--cache-to", "-o", "--output"}
DOCKER_WITHOUT_FILES = {"volume", "rm", "stop", "start", "restart", "logs", "exec", "ps", "pull", "push",
                        "tag", "images", "inspect"}
COMPOSE_FILES = ("compose.yaml", "compose.yml", "docker-compose.yaml", "docker-compose.yml")


def _compose_missing(args: list[str], root: Path) -> list[str]:
    files = _values_after(args, "-f", "--file")
    if files:
        return [problem for path in files for problem in _missing(path, root, "compose file")]
    if any((root / name).is_file() for name in COMPOSE_FILES):
        return []
    return ["docker compose without -f, and no compose file at the top of the repository"]


def _docker_missing(args: list[str], root: Path) -> list[str]:
    if not args:
        return []
    sub, rest = args[0], args[1:]
    if sub == "build":
        files = _values_after(rest, "-f", "--file")
        if files:
            return [problem for path in files for problem in _missing(path, root, "Dockerfile")]
        positional = [arg for i, arg in enumerate(rest)
                      if not arg.startswith("-") and (i == 0 or rest[i - 1] not in DOCKER_VALUE_OPTIONS)]
        return _missing(str(Path(positional[-1] if positional else ".") / "Dockerfile"), root, "Dockerfile")
    if sub == "run":
        return _missing("Dockerfile", root, "the image's Dockerfile")
    if sub == "compose":
        return _compose_missing(rest, root)
    if sub in DOCKER_WITHOUT_FILES:
        return []
    return [f"docker {sub}: a docker command this test does not know"]


def _kubectl_missing(args: list[str], root: Path) -> list[str]:
    files = _values_after(args, "-f", "--filename", "-k", "--kustomize")
    if args[:1] == ["apply"] and not files:
        return ["kubectl apply without -f or -k"]
    return [problem for path in files for problem in _missing(path, root, "manifest")]


def command_problems(words: list[str], root: Path = ROOT) -> list[str]:
    """What a simple command names that does not exist, or [] if all of it does; a command this test
    has no check for must be in ``ALLOWED``."""
    name, args = words[0], words[1:]
    base = name.rsplit("/", 1)[-1]
    if name == "make":
        targets = [arg for i, arg in enumerate(args) if not arg.startswith("-") and "=" not in arg
                   and (i == 0 or args[i - 1] not in ("-C", "-f", "-j", "-o", "-W"))]
        return [f"make {t}: no such target in the Makefile" for t in targets if t not in make_targets(root)]
    if PYTHON.fullmatch(base):
        return _python_missing(args, root)
    if base in ("pytest", "py.test"):
        return _pytest_missing(args, root)
    if name in ("bash", "sh"):
        scripts = [arg for arg in args if not arg.startswith("-")]
        return [] if "-c" in args or not scripts else _missing(scripts[0], root, "script")
    if name == "docker":
        return _docker_missing(args, root)
    if name == "docker-compose":
        return _compose_missing(args, root)
    if name == "kubectl":
        return _kubectl_missing(args, root)
    if name == "streamlit" and args[:1] == ["run"]:
        return _missing(args[1], root, "app") if len(args) > 1 else ["streamlit run without an app"]
    if "/" in name:
        return _missing(name, root, "program")
    if name in ALLOWED:
        return []
    return [f"{name}: not a command this test knows; check what it names, or add it to ALLOWED"]


def doc_command_problems(doc: Path, text: str, root: Path = ROOT) -> list[str]:
    """Every problem of every command in ``text``'s shell blocks, with where it stands."""
    return [f"{doc.name}:{line}: {command_line.strip()}: {problem}"
            for line, command_line in shell_commands(text)
            for words in simple_commands(command_line)
            for problem in command_problems(words, root)]


# ---------------------------------------------------------------- the documents

def _id(doc: Path) -> str:
    return str(doc.relative_to(ROOT))


@pytest.mark.parametrize("doc", DOCS, ids=_id)
def test_every_relative_link_and_anchor_resolves(doc):
    """Each relative link and image of the document reaches a file or directory of the repository,
    and each #anchor a heading of its Markdown target."""
    assert broken_links(doc, doc.read_text(encoding="utf-8")) == []


@pytest.mark.parametrize("doc", DOCS, ids=_id)
def test_every_command_in_a_shell_block_names_what_exists(doc):
    """Each command in the document's bash/sh/shell/console blocks names a Makefile target, a file,
    a module, a Dockerfile, a compose file or a manifest that exists, or is an allowed kind."""
    assert doc_command_problems(doc, doc.read_text(encoding="utf-8")) == []


@pytest.mark.parametrize("name", sorted(LONGEST))
def test_the_top_level_documents_stay_short(name):
    """README.md within 250 lines and BENCHMARKS.md within 400: the rest belongs in docs/ by reader,
    and a benchmark's older rounds in docs/benchmarks-log.md."""
    lines = (ROOT / name).read_text(encoding="utf-8").count("\n")
    assert lines <= LONGEST[name], f"{name} has {lines} lines, more than {LONGEST[name]}"


def test_the_quick_start_is_make_run_then_make_test():
    """The README's only shell commands, its quick start, are ``make run`` and then ``make test``."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    commands = [words for _, line in shell_commands(readme) for words in simple_commands(line)]
    assert commands == [["make", "run"], ["make", "test"]]


def test_the_documents_give_these_checks_something_to_check():
    """Not vacuous: the documents hold dozens of relative links, ten or more with an anchor; the
    README links the index, docs/README.md, and the index links every other page of docs/; the shell
    blocks hold commands of several kinds."""
    texts = {doc: doc.read_text(encoding="utf-8") for doc in DOCS}
    relative = [t for text in texts.values() for _, t in links(text) if not re.match(r"[a-z]+:", t)]
    assert len(relative) >= 30 and sum("#" in t for t in relative) >= 10

    def linked_from(doc):
        return {(doc.parent / t.partition("#")[0]).resolve() for _, t in links(texts[doc])}

    index = ROOT / "docs" / "README.md"
    assert index in linked_from(ROOT / "README.md")
    assert [doc.name for doc in DOCS if doc.parent == index.parent and doc != index
            and doc not in linked_from(index)] == []
    kinds = {words[0] for text in texts.values() for _, line in shell_commands(text)
             for words in simple_commands(line)}
    assert {"make", "docker"} <= kinds


# ---------------------------------------------------------------- the checks can fail

CONTROL = """# A control

[a file that is not there](no/such/file.md), [an anchor that is not there](#nowhere),
[one that is](#a-control), [the README](../README.md#quick-start) and
![a picture that is not there](missing.png); `[in code](no/such/code.md)` is not a link.

```sh
make no-such-target
frobnicate --all
python no/such/script.py
docker compose -f deploy/no-such-compose.yml up -d
```
"""


def test_the_checks_report_a_broken_link_a_missing_anchor_an_unknown_target_and_an_unlisted_command():
    """Positive control: the same functions, on a small text placed in docs/, report the missing
    file, the missing anchor and the missing picture (and not the good links, nor the link in code),
    and the unknown make target, the unlisted command, the missing script and compose file."""
    doc = ROOT / "docs" / "control.md"
    reported = broken_links(doc, CONTROL)
    assert len(reported) == 3
    assert any(r.startswith("control.md:3: (no/such/file.md)") and "no such file" in r for r in reported)
    assert any(r.startswith("control.md:3: (#nowhere)") and "no heading" in r for r in reported)
    assert any(r.startswith("control.md:5: (missing.png)") for r in reported)
    problems = doc_command_problems(doc, CONTROL)
    assert len(problems) == 4
    assert "no-such-target: no such target" in problems[0]
    assert "frobnicate: not a command this test knows" in problems[1]
    assert "script no/such/script.py does not exist" in problems[2]
    assert "compose file deploy/no-such-compose.yml does not exist" in problems[3]


def test_github_slugs_drop_punctuation_and_number_repeated_headings():
    """Anchors as GitHub makes them, the duplicates' ``-1`` included."""
    assert github_slug("Inside the LMS (LTI 1.3)") == "inside-the-lms-lti-13"
    assert github_slug("7. Fair share: one session floods, a class works (issue 25)") == \
        "7-fair-share-one-session-floods-a-class-works-issue-25"
    assert github_slug("The files of a problem `<pid>`") == "the-files-of-a-problem-pid"
    assert github_slug("A lecture's burst in Practice") == "a-lectures-burst-in-practice"
    text = "# Setup\n\n```sh\n# not a heading\n```\n\n## Setup\n\n### Setup ###\n"
    assert heading_anchors(text) == {"setup", "setup-1", "setup-2"}


def test_a_command_line_is_split_as_the_shell_would_split_it():
    """Assignments before a command, ``&&`` chains, a continued line, a subshell, a redirection, a
    command substitution and a comment are read as the shell reads them."""
    block = ("```console\n$ DL_X=1 make run && \\\n    make test   # both\noutput, not a command\n"
             "$ (umask 077; printf '%s\\n' \"K=$(openssl rand -hex 32)\" > /etc/env)\n```\n")
    commands = [words for _, line in shell_commands(block) for words in simple_commands(line)]
    assert commands == [["make", "run"], ["make", "test"], ["umask", "077"],
                        ["printf", "%s\\n", "K=SUBSTITUTED"], ["openssl", "rand", "-hex", "32"]]
    assert simple_commands("sudo -E flock /tmp/x.lock python -m pytest tests/house/test_docs.py") == \
        [["python", "-m", "pytest", "tests/house/test_docs.py"]]
