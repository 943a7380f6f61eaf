#!/usr/bin/env python3
"""The documentation test: the commands of README.md and docs/*.md are the program's.

Every fenced ``sh`` block that calls ``fluidbed`` is checked and, unless marked long, run as one
script (``set -e``) in a fresh folder holding a link to the source tree's ``assets/``, with the
build's program first on PATH, as an installed user would type it. Checked for every such block:
each verb is one ``fluidbed --help`` lists and each option one ``fluidbed VERB --help`` accepts;
each scene, lesson, script and file it names exists (in the source tree, or written by the block
before it is named); each study it names is one ``fluidbed study --list`` lists. Checked for every
page: its relative links lead to files that exist, and it is not over its length.

Every fenced ``python`` block that imports fluidbed is run the same way with ``--python`` (the
build tree's package on PYTHONPATH, ``--python-path``); without ``--python-path`` (a build without
the module) it is skipped.

An HTML comment on the lines just before a block says what to do with it:
  <!-- doc: long -->           check the block, do not run it;
  <!-- doc: until T -->        run it with every ``--until`` of a run, bench, view or sweep set to T
                               (added where a run, bench or view has none);
  <!-- doc: exits N -->        it must end with exit status N (default 0);
  <!-- doc: set KEY=VALUE -->  add ``--set KEY=VALUE`` to each of its fluidbed commands that
                               takes --set;
  <!-- doc: file NAME -->      the page's last ``text`` block above it is the file NAME, written
                               into the folder of this block and of every later one of the page.

Usage: check_docs.py --program PATH --source DIR --work DIR [--cache DIR] [--page FILE ...]
                     [--python PYTHON --python-path DIR]
Exit status 0 when every check passes, 1 otherwise (each failure one line: page:line: what).
"""
import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import time

MAX_LINES = {"README.md": 150}
MAX_PAGE_LINES = 400
RUN_TIMEOUT_S = 600

MARKER = re.compile(r"^\s*<!--\s*doc:\s*(\w+)\s*(.*?)\s*-->\s*$")
FENCE = re.compile(r"^\s*```\s*([\w+-]*)\s*$")
# A fluidbed command: the word at the start of a command (not a path or a file name).
COMMAND_START = re.compile(r"(?:^|[;&|(]\s*|\bthen\s+|\bdo\s+)\s*fluidbed(?=\s|$)")
LINK = re.compile(r"\]\(([^)#\s]+)(?:#[^)]*)?\)")


class Block:
    def __init__(self, page, line, lang, text, markers):
        self.page, self.line, self.lang, self.text, self.markers = page, line, lang, text, markers

    def marker(self, name):
        return [value for key, value in self.markers if key == name]

    def where(self):
        return f"{self.page}:{self.line}"


def read_blocks(path, page):
    """The fenced blocks of a Markdown file, each with the markers on the lines just before it."""
    blocks, markers, lines = [], [], open(path, encoding="utf-8").read().split("\n")
    k = 0
    while k < len(lines):
        m = MARKER.match(lines[k])
        f = FENCE.match(lines[k])
        if m:
            markers.append((m.group(1), m.group(2)))
        elif f:
            start, body = k + 1, []
            k += 1
            while k < len(lines) and not re.match(r"^\s*```\s*$", lines[k]):
                body.append(lines[k])
                k += 1
            blocks.append(Block(page, start, f.group(1), "\n".join(body) + "\n", markers))
            markers = []
        elif lines[k].strip():
            markers = []
        k += 1
    return blocks, lines


def logical_lines(text):
    """Lines with backslash continuations joined."""
    out, current = [], ""
    for line in text.split("\n"):
        if line.endswith("\\"):
            current += line[:-1] + " "
        else:
            out.append(current + line)
            current = ""
    if current:
        out.append(current)
    return out


def strip_comment(line):
    """The line without a trailing shell comment (a # that starts a word, outside quotes)."""
    quote = None
    for i, c in enumerate(line):
        if quote:
            if c == quote:
                quote = None
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or line[i - 1].isspace()):
            return line[:i]
    return line


def fluidbed_commands(text):
    """Each fluidbed command of a block as (its words, the logical line it is on)."""
    commands = []
    for line in logical_lines(text):
        code = strip_comment(line)
        for m in COMMAND_START.finditer(code):
            rest = code[m.end():]
            # The command ends at the next operator or redirection.
            end = re.search(r"\s(?:&&|\|\||;|\||>|<|2>)|\)", rest)
            segment = rest[: end.start()] if end else rest
            try:
                words = shlex.split(segment)
            except ValueError:
                words = segment.split()
            commands.append((words, line))
    return commands


class Program:
    """What the program accepts, read off its own help."""

    def __init__(self, path):
        self.path = path
        top = self.help([])
        section = top.split("Subcommands:", 1)[1] if "Subcommands:" in top else ""
        self.verbs = set(re.findall(r"^\s{2}([a-z][\w-]*)\s", section, re.M))
        self.top_options = set(re.findall(r"(--[a-z][\w-]*)", top.split("Subcommands:", 1)[0]))
        self.options = {}
        self.studies = None

    def help(self, args):
        r = subprocess.run([self.path] + args + ["--help"], capture_output=True, text=True)
        return r.stdout + r.stderr

    def verb_options(self, verb):
        if verb not in self.options:
            self.options[verb] = set(re.findall(r"(--[a-z][\w-]*)", self.help([verb])))
        return self.options[verb]

    def study_names(self):
        if self.studies is None:
            r = subprocess.run([self.path, "study", "--list"], capture_output=True, text=True)
            self.studies = set(re.findall(r"^([a-z][\w-]*)\s", r.stdout, re.M))
        return self.studies


def looks_like_path(word):
    return ("/" in word or re.search(r"\.(toml|txt|sh|state|md|png|csv)$", word)) and not (
        word.startswith("-") or "=" in word or word.startswith("$") or "://" in word)


def check_block(block, program, source, written, failures):
    """Options, verbs, studies and paths of a block's fluidbed commands."""
    for words, line in fluidbed_commands(block.text):
        if not words or words[0].startswith("-"):
            for w in words:
                name = w.split("=", 1)[0]
                if name.startswith("--") and name not in program.top_options:
                    failures.append(f"{block.where()}: fluidbed has no option {name}: {line.strip()}")
            continue
        verb = words[0]
        if verb not in program.verbs:
            failures.append(f"{block.where()}: fluidbed has no verb '{verb}': {line.strip()}")
            continue
        accepted = program.verb_options(verb)
        for k, w in enumerate(words[1:], start=1):
            name = w.split("=", 1)[0]
            if name.startswith("--") and name not in accepted:
                failures.append(f"{block.where()}: fluidbed {verb} has no option {name}: {line.strip()}")
            if name == "--lesson" and k + 1 < len(words):
                lesson = os.path.join(source, "assets", "lessons", words[k + 1] + ".txt")
                if not os.path.isfile(lesson) and not os.path.isfile(words[k + 1]):
                    failures.append(f"{block.where()}: no lesson '{words[k + 1]}' in assets/lessons")
        if verb == "study":
            positional = [w for k, w in enumerate(words[1:], start=1)
                          if not w.startswith("-") and not words[k - 1].startswith("--")]
            for name in positional[:1]:
                if name not in program.study_names():
                    failures.append(f"{block.where()}: no study '{name}' (fluidbed study --list)")
    # Every file a block names that is not made by a run: in the source tree, written by a file
    # marker, or written by the block itself (a redirection).
    written = set(written) | set(re.findall(r">\s*([^\s;&|]+)", block.text))
    for line in logical_lines(block.text):
        code = strip_comment(line)
        try:
            words = shlex.split(code)
        except ValueError:
            words = code.split()
        for w in words:
            for part in w.split(","):
                p = part.split("=", 1)[1] if "=" in part and part.startswith("--") else part
                if not looks_like_path(p) or p.startswith(("out/", "build", "/", "~", "./out")):
                    continue
                if p.startswith(("assets/", "scripts/", "docs/", "tests/", ".ci/")) or (
                        "/" not in p and p.endswith((".toml", ".txt", ".sh"))):
                    if not (os.path.exists(os.path.join(source, p)) or p in written):
                        failures.append(f"{block.where()}: names {p}, which does not exist")


def transformed(block, program):
    """The block's script with its markers applied (--until, --set)."""
    until = block.marker("until")
    sets = block.marker("set")
    if not until and not sets:
        return block.text
    out = []
    for line in logical_lines(block.text):
        code = strip_comment(line)
        comment = line[len(code):]
        pieces, pos = [], 0
        for m in COMMAND_START.finditer(code):
            rest = code[m.end():]
            end = re.search(r"\s(?:&&|\|\||;|\||>|<|2>)|\)", rest)
            stop = m.end() + (end.start() if end else len(rest.rstrip()))
            command = code[m.end():stop]
            words = command.split()
            verb = words[0] if words else ""
            if until and verb in ("run", "bench", "view", "sweep"):
                if re.search(r"--until[ =]\S+", command):
                    command = re.sub(r"--until([ =])\S+", r"--until\g<1>" + until[0], command)
                elif verb != "sweep" and "--resume" not in command:
                    command += " --until " + until[0]
            if sets and "--set" in program.verb_options(verb) and "--resume" not in command:
                command += "".join(" --set " + s for s in sets)
            pieces.append(code[pos:m.end()] + command)
            pos = stop
        pieces.append(code[pos:])
        out.append("".join(pieces) + comment)
    return "\n".join(out) + "\n"


def run_block(block, program, source, work, cache, files, failures, python=None):
    folder = os.path.join(work, f"{block.page.replace('/', '_')}-{block.line}")
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    os.symlink(os.path.join(source, "assets"), os.path.join(folder, "assets"))
    for name, text in files.items():
        target = os.path.join(folder, name)
        os.makedirs(os.path.dirname(target) or folder, exist_ok=True)
        with open(target, "w", encoding="utf-8") as f:
            f.write(text)
    if python:
        script = block.text
        with open(os.path.join(folder, "block.py"), "w", encoding="utf-8") as f:
            f.write(script)
        command = [python[0], "block.py"]
    else:
        script = "set -euo pipefail\n" + transformed(block, program)
        with open(os.path.join(folder, "block.sh"), "w", encoding="utf-8") as f:
            f.write(script)
        command = ["bash", "block.sh"]
    env = dict(os.environ)
    env["PATH"] = os.path.dirname(os.path.abspath(program.path)) + os.pathsep + env.get("PATH", "")
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    env.pop("FLUIDBED_ASSETS", None)
    if cache:
        env["FLUIDBED_CACHE"] = cache
    if python:
        env["PYTHONPATH"] = python[1]
    expected = int(block.marker("exits")[0]) if block.marker("exits") else 0
    start = time.monotonic()
    try:
        r = subprocess.run(command, cwd=folder, env=env, capture_output=True,
                           text=True, timeout=RUN_TIMEOUT_S)
        status, output = r.returncode, r.stdout + r.stderr
    except subprocess.TimeoutExpired:
        status, output = None, f"no end within {RUN_TIMEOUT_S} s"
    took = time.monotonic() - start
    print(f"{block.where()}: exit {status} in {took:.1f} s (expected {expected})", flush=True)
    if status != expected:
        tail = "\n    ".join(output.strip().split("\n")[-8:])
        failures.append(f"{block.where()}: exit {status}, expected {expected}; the script:\n"
                        f"    {script.strip()}\n  its last lines:\n    {tail}")
    else:
        shutil.rmtree(folder, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--program", required=True)
    ap.add_argument("--source", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--cache", default="")
    ap.add_argument("--page", action="append", default=[], help="only these pages (relative)")
    ap.add_argument("--python", default="", help="the Python the module was built for")
    ap.add_argument("--python-path", default="", help="the build tree's package folder")
    a = ap.parse_args()
    source = os.path.abspath(a.source)
    program = Program(os.path.abspath(a.program))
    if not program.verbs:
        print(f"{a.program} --help lists no verbs", file=sys.stderr)
        return 1
    pages = a.page or ["README.md"] + sorted(
        "docs/" + f for f in os.listdir(os.path.join(source, "docs")) if f.endswith(".md"))
    os.makedirs(a.work, exist_ok=True)
    failures, ran, checked = [], 0, 0
    for page in pages:
        path = os.path.join(source, page)
        blocks, lines = read_blocks(path, page)
        limit = MAX_LINES.get(page, MAX_PAGE_LINES)
        if len(lines) > limit + 1:
            failures.append(f"{page}: {len(lines) - 1} lines, over its {limit}")
        for n, line in enumerate(lines, start=1):
            for target in LINK.findall(line):
                if "://" in target or target.startswith("mailto:"):
                    continue
                if not os.path.exists(os.path.join(os.path.dirname(path), target)):
                    failures.append(f"{page}:{n}: the link {target} leads nowhere")
        files, last_text = {}, None
        for block in blocks:
            for name in block.marker("file"):
                if last_text is None:
                    failures.append(f"{block.where()}: a file marker with no text block above it")
                else:
                    files[name] = last_text.text
            if block.lang == "text":
                last_text = block
            if block.lang == "python" and "import fluidbed" in block.text:
                if a.python and a.python_path and not block.marker("long"):
                    run_block(block, program, source, a.work, a.cache, files, failures,
                              (a.python, a.python_path))
                    ran += 1
                continue
            if block.lang not in ("sh", "bash") or not fluidbed_commands(block.text):
                continue
            checked += 1
            check_block(block, program, source, set(files), failures)
            if not block.marker("long"):
                run_block(block, program, source, a.work, a.cache, files, failures)
                ran += 1
    print(f"{len(pages)} pages, {checked} blocks with fluidbed commands checked, {ran} run")
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
