#!/usr/bin/env python3
"""Checks that the user documentation names only what exists.

    check_doc_names.py --shard SHARD --root REPO [PAGE ...]

For every page (default: README.md and every docs/**/*.md under REPO) it fails, naming the page and
line, when the page names
  - a repository file or folder that does not exist (a path starting with one of the top-level
    folders below, or a relative Markdown link),
  - a link to a section (`page.md#anchor`, `#anchor`) whose page has no heading of that anchor,
  - a section named in quotes after its page (`docs/x.md, "Noise"`) that is neither a heading nor a
    bold paragraph title of that page,
  - a `shard` subcommand that `shard --help` does not list,
  - a `--option` on a `shard SUBCOMMAND` command line that the subcommand's `--help` does not list.
Commands are read from code only (fenced blocks and `inline code`), where prose cannot be
mistaken for one. Exit code 0 when all names exist, 1 otherwise.
"""
import argparse
import pathlib
import re
import subprocess
import sys

# Not geometry/: scenes name their meshes geometry/NAME.stl, relative to the scene's folder.
TOP_FOLDERS = ("plugin_api", "io", "h5", "kernel", "plugins", "analysis", "driver", "apps", "scenes",
               "tests", "bench", "cmake", "templates", "docs", ".ci")
# A path inside the repository: a top-level folder, then at least one more part. Not preceded by a
# path character (build/release/tests/... is a build folder, not the repository's tests/).
REPO_PATH = re.compile(r"(?<![\w./$-])((?:%s)/[\w.+/-]*\w)" % "|".join(re.escape(f) for f in TOP_FOLDERS))
LINK = re.compile(r"\]\(([^)\s]+)\)")
# A page, then a section of it in quotes: docs/explanation/diagnosis.md, "Noise".
QUOTED_SECTION = re.compile(r"([\w./-]+\.md),?\s+\"([^\"]{3,80})\"")
# `shard` as a program, then global options, then the subcommand.
COMMAND = re.compile(r"(?<![\w.:/-])(?:[\w./$]*/)?shard((?:\s+--plugin-dir\s+\S+)*)\s+([a-z][a-z-]*)(?![\w])")
OPTION = re.compile(r"(?<![\w-])(--[a-z][a-z0-9-]*)")
# A path followed by one of these is a pattern (a glob, a placeholder), not a file.
PATTERN_MARKS = ("*", "<", "{", "...")
# Fenced blocks in these languages hold shell commands; others (toml, cpp, python) may say "shard"
# in a comment.
SHELL_FENCES = ("", "sh", "bash", "shell", "console", "text")
# `shard calibrate MEAS --with E` runs calibrate-effect, `shard diagnose A B` diagnose-sets, and
# `shard calibrate REF SET --reference REF --with E` calibrate-contrast (apps/src/command_routing.cpp):
# their options belong to the command a user types.
ROUTED = {"calibrate": ("calibrate-effect", "calibrate-contrast"), "diagnose": ("diagnose-sets",)}


def help_text(shard, words):
    done = subprocess.run([shard, *words, "--help"], capture_output=True, text=True, timeout=60)
    return done.stdout + done.stderr


class Commands:
    """The subcommands `shard --help` lists, and hidden ones whose own --help is theirs (for an
    unknown word `shard WORD --help` prints the program's help)."""

    def __init__(self, shard):
        self.shard = shard
        text = help_text(shard, [])
        parts = re.split(r"SUBCOMMANDS:|Subcommands:", text, maxsplit=1)
        head, listed = parts[0], parts[-1] if len(parts) > 1 else ""
        self.listed = set(re.findall(r"^\s+([a-z][a-z-]*)\s", listed, re.M))
        if not self.listed:
            sys.exit(f"check_doc_names: no subcommands in `{shard} --help`:\n{text}")
        self.global_options = set(OPTION.findall(head))
        self.hidden = {}

    def exists(self, name):
        if name in self.listed:
            return True
        if name not in self.hidden:
            usage = re.search(r"Usage: \S*shard (\S+)", help_text(self.shard, [name]))
            self.hidden[name] = bool(usage) and usage.group(1) == name
        return self.hidden[name]


class Options:
    """Each subcommand's options, read from its --help once."""

    def __init__(self, shard, global_options):
        self.shard, self.global_options, self.known = shard, global_options, {}

    def of(self, command):
        if command not in self.known:
            names = set(self.global_options) | {"--help"}
            for word in (command, *ROUTED.get(command, ())):
                names |= set(OPTION.findall(help_text(self.shard, [word])))
            self.known[command] = names
        return self.known[command]


def heading_anchors(text):
    """The anchors GitHub gives a page's headings: lower case, punctuation but '-' and '_' dropped,
    blanks made '-', a repeated anchor numbered -1, -2, ..."""
    anchors, seen, in_block = set(), {}, False
    for line in text.splitlines():
        if line.lstrip().startswith("```"):
            in_block = not in_block
        heading = None if in_block else re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
        if heading:
            anchor = re.sub(r"[^\w\- ]", "", heading.group(1).lower()).replace(" ", "-")
            anchors.add(anchor if anchor not in seen else f"{anchor}-{seen[anchor]}")
            seen[anchor] = seen.get(anchor, 0) + 1
    return anchors


def section_titles(text):
    """The page's headings and bold paragraph titles (**Noise.**), lower case."""
    titles = [m.group(1) for m in re.finditer(r"^#{1,6}\s+(.*?)\s*#*\s*$", text, re.MULTILINE)]
    titles += re.findall(r"\*\*([^*]+)\*\*", text)
    return [" ".join(t.lower().split()) for t in titles]


def page_named(page, name, root):
    """The page a text names: beside the page, from the repository root, or under docs/."""
    for candidate in (page.parent / name, root / name, *sorted((root / "docs").rglob(pathlib.Path(name).name))):
        if candidate.is_file():
            return candidate
    return None


def section_problems(page, text, root):
    problems = []
    for match in QUOTED_SECTION.finditer(text):
        name, section = match.group(1), " ".join(match.group(2).split())
        named = page_named(page, name, root)
        if named and not any(section.lower() in title for title in section_titles(named.read_text(encoding="utf-8"))):
            number = text.count("\n", 0, match.start()) + 1
            problems.append((number, f"names the section \"{section}\" of {name}, which has no such heading or bold "
                                     "title"))
    return problems


def code_lines(text):
    """(line number, code) for every line of a shell code block (continuations joined) and every
    inline code span."""
    in_block, shell, joined, start = False, False, "", 0
    for number, line in enumerate(text.splitlines(), 1):
        if line.lstrip().startswith("```"):
            in_block = not in_block
            shell = line.strip().strip("`").strip() in SHELL_FENCES
            continue
        if in_block and not shell:
            continue
        if in_block:
            if not joined:
                start = number
            joined += line.rstrip("\\") + " "
            if not line.rstrip().endswith("\\"):
                yield start, joined
                joined = ""
        else:
            for span in re.findall(r"`([^`]+)`", line):
                yield number, span


def command_problems(code, commands, options):
    problems = []
    # A line may chain commands (&&, |, ;); a # starts a comment.
    for part in re.split(r"&&|\|\||[|;]|\s#\s", code):
        match = COMMAND.search(part)
        if not match:
            continue
        name = match.group(2)
        if not commands.exists(name):
            problems.append(f"`shard {name}` is no shard subcommand (shard --help lists: {', '.join(sorted(commands.listed))})")
            continue
        for option in OPTION.findall(part[match.end():]):
            if option not in options.of(name):
                problems.append(f"`shard {name} {option}`: `shard {name} --help` lists no {option}")
    return problems


def path_problems(page, text, root):
    problems = []
    for number, line in enumerate(text.splitlines(), 1):
        for match in REPO_PATH.finditer(line):
            path = match.group(1)
            if line[match.end():].startswith(PATTERN_MARKS) or any(mark in path for mark in PATTERN_MARKS):
                continue
            if not (root / path).exists():
                problems.append((number, f"names {path}, which is not in the repository"))
        for target in LINK.findall(line):
            if re.match(r"[a-z]+:", target):
                continue
            path, _, anchor = target.partition("#")
            linked = page.parent / path if path else page
            if path and not linked.exists():
                problems.append((number, f"links to {path}, which does not exist beside the page"))
            elif anchor and linked.suffix == ".md" and anchor not in heading_anchors(linked.read_text(encoding="utf-8")):
                problems.append((number, f"links to {target}, but {linked.name} has no heading #{anchor}"))
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shard", required=True)
    parser.add_argument("--root", required=True, type=pathlib.Path)
    parser.add_argument("pages", nargs="*", type=pathlib.Path)
    args = parser.parse_args()
    root = args.root.resolve()
    pages = args.pages or [root / "README.md", *sorted((root / "docs").rglob("*.md"))]
    commands = Commands(args.shard)
    options = Options(args.shard, commands.global_options)
    failures = 0
    for page in pages:
        text = page.read_text(encoding="utf-8")
        problems = path_problems(page, text, root) + section_problems(page, text, root)
        for number, code in code_lines(text):
            problems += [(number, p) for p in command_problems(code, commands, options)]
        for number, problem in sorted(problems):
            print(f"{page}:{number}: {problem}")
        failures += len(problems)
    print(f"{len(pages)} pages checked: {failures} names that do not exist")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
