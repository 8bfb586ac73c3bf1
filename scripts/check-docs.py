#!/usr/bin/env python3
"""Checks the user's guide (README.md) and the pages under docs/.

  scripts/check-docs.py               history: no dates, commit hashes or issue references (git
                                      keeps the history; a page states what is true now)
  scripts/check-docs.py --commands B  every `candela CMD ...` the pages show names a command of
                                      the binary B, and every --option it passes is one that
                                      `B help CMD` lists

Prints each finding as FILE:LINE: what, and exits 1 if there is any.
"""
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

MONTHS = ("January|February|March|April|May|June|July|August|September|October|November|"
          "December|Jan|Feb|Mar|Apr|Jun|Jul|Aug|Sep|Sept|Oct|Nov|Dec")
HISTORY = [
    (re.compile(r"\b(19|20)\d\d-[01]\d-[0-3]\d\b"), "a date"),
    (re.compile(rf"\b({MONTHS})\.? (\d{{1,2}}, )?(19|20)\d\d\b"), "a date"),
    (re.compile(rf"\b\d{{1,2}} ({MONTHS}) (19|20)\d\d\b"), "a date"),
    (re.compile(r"\b(issue|stop|PR|pull request)s? ?#?\d+", re.I), "an issue reference"),
    (re.compile(r"\b(commit|hash|revision) [0-9a-f]{7,40}\b", re.I), "a commit hash"),
    (re.compile(r"\bsince (then|commit|the last|the previous|last time)\b", re.I), "history"),
]
# A bare hexadecimal word of 7 to 40 characters with digits and letters: a commit hash, unless it
# is a colour (#rrggbb) or a constant (0x...).
HASH = re.compile(r"(?<![#\w/.-])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}(?![\w.-])")


def pages():
    yield ROOT / "README.md"
    yield from sorted((ROOT / "docs").rglob("*.md"))


def check_history():
    found = []
    for page in pages():
        for n, line in enumerate(page.read_text().splitlines(), 1):
            where = f"{page.relative_to(ROOT)}:{n}"
            for pattern, what in HISTORY:
                m = pattern.search(line)
                if m:
                    found.append(f"{where}: {what} ({m.group(0)!r})")
            for m in HASH.finditer(line):
                found.append(f"{where}: a commit hash ({m.group(0)!r})")
    return found


# `candela CMD args`, in inline code or in a code block line; ./build/candela and build/candela too.
COMMAND = re.compile(r"(?:^|[\s`(])(?:\./)?(?:build/)?candela ([a-z][\w-]*)((?: +[^`\s|;&)]+)*)")


def help_options(binary, command, cache={}):
    if command not in cache:
        run = subprocess.run([binary, "help", command], capture_output=True, text=True)
        cache[command] = (None if run.returncode != 0 else
                          set(re.findall(r"(?<![\w-])(--[a-z][\w-]*)", run.stdout)))
    return cache[command]


def check_commands(binary):
    found, shown = [], 0
    for page in pages():
        in_block = False
        for n, line in enumerate(page.read_text().splitlines(), 1):
            if line.lstrip().startswith("```"):
                in_block = not in_block
                continue
            # Outside a code block only inline code counts: prose says "candela" too.
            texts = [line] if in_block else re.findall(r"`([^`]*)`", line)
            for text in texts:
                for m in COMMAND.finditer(" " + text):
                    command, rest = m.group(1), m.group(2)
                    if command in ("help",):
                        continue
                    shown += 1
                    where = f"{page.relative_to(ROOT)}:{n}"
                    options = help_options(binary, command)
                    if options is None:
                        found.append(f"{where}: `candela {command}` is no command of {binary}")
                        continue
                    for option in re.findall(r"(?<![\w-])(--[a-z][\w-]*)", rest):
                        if option not in options and option not in ("--help", "--version"):
                            found.append(f"{where}: `candela {command}` has no option {option}")
    return found, shown


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--commands":
        found, shown = check_commands(sys.argv[2])
        summary = f"check-docs: {shown} commands shown in the docs, each as its help lists it"
    elif len(sys.argv) == 1:
        found = check_history()
        summary = "check-docs: no dates, commit hashes or issue references in README.md and docs/"
    else:
        print(__doc__)
        return 2
    for f in found:
        print(f)
    if found:
        print(f"check-docs: {len(found)} finding(s)")
        return 1
    print(summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
