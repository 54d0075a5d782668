#!/usr/bin/env python3
"""docs/reference/cli.md shows every command's --help verbatim: each ```text block under a heading
"## shard" or "### shard COMMAND" must be what `shard [COMMAND] --help` prints, and every
subcommand `shard --help` lists must have such a block.

  check_cli_reference.py --shard BIN PAGE           exit 1 listing the blocks that differ or lack
  check_cli_reference.py --shard BIN PAGE --write   rewrite the differing blocks from the binary
"""
import argparse
import re
import subprocess
import sys

HEADING = re.compile(r"^#{2,3} shard( [a-z-]+)?\s*$")


def help_text(shard, command):
    args = [shard] + ([command] if command else []) + ["--help"]
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    # The usage line names the binary as it was called; the page names it as users call it.
    return [re.sub(r"^Usage: \S+", "Usage: shard", line) for line in out.rstrip("\n").split("\n")]


def subcommands(shard):
    """The subcommands `shard --help` lists, in its order."""
    listed = help_text(shard, "")
    start = listed.index("Subcommands:") + 1
    return [m.group(1) for line in listed[start:] if (m := re.match(r"^\s+([a-z][a-z-]*)\s", line))]


def blocks(lines):
    """(command, first line, end line) of the text block after each command heading."""
    command = None
    for i, line in enumerate(lines):
        m = HEADING.match(line)
        if m:
            command = (m.group(1) or "").strip()
            continue
        if command is not None and line.strip() == "```text":
            end = next(k for k in range(i + 1, len(lines)) if lines[k].strip() == "```")
            yield command, i + 1, end
            command = None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--shard", required=True)
    ap.add_argument("page")
    ap.add_argument("--write", action="store_true")
    a = ap.parse_args()
    lines = open(a.page, encoding="utf-8").read().split("\n")
    stale = []
    for command, first, end in reversed(list(blocks(lines))):
        current = help_text(a.shard, command)
        if lines[first:end] != current:
            stale.append(f"shard {command} --help" if command else "shard --help")
            lines[first:end] = current
    if a.write:
        open(a.page, "w", encoding="utf-8").write("\n".join(lines))
    for command in reversed(stale):
        print(f"{a.page}: the block of `{command}` differs from the binary's"
              + ("; rewritten" if a.write else ""))
    documented = {command for command, _, _ in blocks(lines)}
    missing = [c for c in subcommands(a.shard) if c not in documented]
    for command in missing:
        print(f"{a.page}: `shard {command}` has no block (add a heading '### shard {command}' and an"
              " empty ```text block under it, then run with --write)")
    if stale and not a.write:
        print(f"Fix: python3 {sys.argv[0]} --shard {a.shard} {a.page} --write")
        return 1
    if missing:
        return 1
    print(f"{a.page}: {len(stale) if a.write else 0} stale blocks")
    return 0


if __name__ == "__main__":
    sys.exit(main())
