#!/usr/bin/env python3
"""Checks the user guide's links (Python 3 standard library only).

Reads docs/src/SUMMARY.md and every chapter in docs/src/, and the draft front page
README.md, and
fails with exit code 1, naming file and line, on:

- a link to a file that does not exist;
- a link to an `#anchor` that no heading of the target chapter produces (mdBook's anchors: the
  heading's text in lower case, spaces to '-', punctuation other than '-' and '_' dropped, a
  repeated heading getting -1, -2, ...);
- a picture (`![alt](pictures/NAME.png)`) whose NAME.png is not listed in docs/pictures.txt;
- a chapter file missing from SUMMARY.md, or a SUMMARY.md entry whose file is missing;
- a malformed line of pictures.txt (`NAME.png<TAB>armlab args...`), or a name listed twice;
- cli.md without exactly one generated-reference marker line.

Pictures themselves are not required to exist yet (they are made by the commands in
pictures.txt). Usage: python3 docs/check_links.py  (from anywhere).
"""

import os
import re
import sys

DOCS = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.join(DOCS, "src")
REPO = os.path.dirname(DOCS)
PICTURES_TXT = os.path.join(DOCS, "pictures.txt")
FRONT = os.path.join(os.path.dirname(DOCS), "README.md")
CLI_MARKER = "<!-- generated from the parser by tests/cli/cli_reference.rs: UPDATE_DOCS=1 cargo test --test cli cli_reference rewrites it; do not edit below -->"

FENCE = re.compile(r"^\s*(```|~~~)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
CODE_SPAN = re.compile(r"(`+)(.+?)\1")
# [text](target) or ![alt](target), with an optional "title".
LINK = re.compile(r"(!?)\[((?:[^\[\]]|\[[^\[\]]*\])*)\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")

errors = []


def error(path, line, message):
    errors.append(f"{os.path.relpath(path, REPO)}:{line}: {message}")


def lines_outside_code(text):
    """(line number, line) for every line not inside a fenced code block."""
    fenced = None
    for number, line in enumerate(text.splitlines(), start=1):
        m = FENCE.match(line)
        if m:
            if fenced is None:
                fenced = m.group(1)
            elif line.strip().startswith(fenced):
                fenced = None
            continue
        if fenced is None:
            yield number, line


def heading_text(raw):
    """The text of a heading as mdBook sees it once rendered: no markup, no tags."""
    text = CODE_SPAN.sub(lambda m: m.group(2), raw)
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links and images: their text
    text = re.sub(r"<[^>]*>", "", text)  # HTML tags
    text = re.sub(r"(\*\*|__|\*)", "", text)  # emphasis markers
    for entity in ("&lt;", "&gt;", "&amp;", "&#39;", "&quot;"):
        text = text.replace(entity, "")
    return text.strip()


def normalize_id(text):
    """mdBook's normalize_id: alphanumerics, '_' and '-' kept (ASCII lower-cased), whitespace to
    '-', everything else dropped."""
    out = []
    for ch in text:
        if ch.isalnum() or ch in "_-":
            out.append(ch.lower() if ch.isascii() else ch)
        elif ch.isspace():
            out.append("-")
    return "".join(out)


_anchor_cache = {}


def anchors_of(path):
    """The set of anchors mdBook makes for the headings of a Markdown file."""
    if path not in _anchor_cache:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        seen = {}
        anchors = set()
        for _, line in lines_outside_code(text):
            m = HEADING.match(line)
            if not m:
                continue
            base = normalize_id(heading_text(m.group(2)))
            count = seen.get(base, 0)
            anchors.add(base if count == 0 else f"{base}-{count}")
            seen[base] = count + 1
        _anchor_cache[path] = anchors
    return _anchor_cache[path]


def read_pictures():
    names = {}
    if not os.path.isfile(PICTURES_TXT):
        error(PICTURES_TXT, 0, "pictures.txt is missing")
        return names
    with open(PICTURES_TXT, encoding="utf-8") as f:
        for number, line in enumerate(f.read().splitlines(), start=1):
            if not line.strip():
                continue
            parts = line.split("\t")
            if len(parts) != 2 or not parts[0].endswith(".png") or "/" in parts[0]:
                error(PICTURES_TXT, number, f"expected 'NAME.png<TAB>armlab args...', found {line!r}")
                continue
            name, command = parts
            if not command.startswith("armlab "):
                error(PICTURES_TXT, number, f"{name}: the command must start with 'armlab ': {command!r}")
            if name not in command.split():
                error(PICTURES_TXT, number, f"{name}: the command does not write {name}")
            if name in names:
                error(PICTURES_TXT, number, f"{name} is listed twice (first on line {names[name]})")
                continue
            names[name] = number
    return names


def check_file(path, pictures, used, picture_prefix, base_dir=None):
    """Checks every link and picture of one Markdown file. Links resolve from `base_dir` (the
    file's folder unless given); `picture_prefix` is where pictures live as seen from there."""
    base_dir = base_dir or os.path.dirname(path)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    count = 0
    for number, line in lines_outside_code(text):
        scan = CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line)  # links in code are text
        for m in LINK.finditer(scan):
            is_image, target = m.group(1) == "!", m.group(3)
            count += 1
            if SCHEME.match(target):
                continue  # http:, https:, mailto: are not checked
            file_part, _, anchor = target.partition("#")
            if is_image:
                if not file_part.startswith(picture_prefix):
                    error(path, number, f"picture {target} is not under {picture_prefix}")
                    continue
                name = file_part[len(picture_prefix):]
                if name not in pictures:
                    error(path, number, f"picture {name} is not listed in docs/pictures.txt")
                else:
                    used.add(name)
                continue
            resolved = os.path.normpath(os.path.join(base_dir, file_part)) if file_part else path
            if not os.path.exists(resolved):
                error(path, number, f"link to a missing file: {target} (from {os.path.relpath(base_dir, REPO) or '.'})")
                continue
            if anchor:
                if not resolved.endswith(".md"):
                    error(path, number, f"anchor on a file that is not Markdown: {target}")
                elif anchor not in anchors_of(resolved):
                    known = ", ".join(sorted(anchors_of(resolved)))
                    error(path, number, f"no anchor #{anchor} in {os.path.relpath(resolved, REPO)} (it has: {known})")
    return count


def summary_chapters(summary):
    """The chapter files SUMMARY.md names, with their lines."""
    chapters = []
    with open(summary, encoding="utf-8") as f:
        text = f.read()
    for number, line in lines_outside_code(text):
        for m in LINK.finditer(line):
            target = m.group(3).partition("#")[0]
            if target and not SCHEME.match(target):
                chapters.append((number, target))
    return chapters


def main():
    pictures = read_pictures()
    used = set()
    summary = os.path.join(SRC, "SUMMARY.md")
    if not os.path.isfile(summary):
        error(summary, 0, "SUMMARY.md is missing")
        print("\n".join(errors))
        return 1
    listed = set()
    for number, target in summary_chapters(summary):
        resolved = os.path.normpath(os.path.join(SRC, target))
        listed.add(resolved)
        if not os.path.isfile(resolved):
            error(summary, number, f"SUMMARY.md names a missing chapter: {target}")
    chapters = []
    for root, _, files in os.walk(SRC):
        for name in sorted(files):
            if name.endswith(".md"):
                chapters.append(os.path.join(root, name))
    links = 0
    for chapter in sorted(chapters):
        if os.path.basename(chapter) != "SUMMARY.md" and chapter not in listed:
            error(chapter, 1, "chapter is not listed in SUMMARY.md")
        links += check_file(chapter, pictures, used, "pictures/")
    cli = os.path.join(SRC, "cli.md")
    if os.path.isfile(cli):
        with open(cli, encoding="utf-8") as f:
            markers = [i for i, l in enumerate(f.read().splitlines(), 1) if l.strip() == CLI_MARKER]
        if len(markers) != 1:
            error(cli, markers[1] if len(markers) > 1 else 1, f"expected exactly one marker line {CLI_MARKER!r}, found {len(markers)}")
    front_files = 0
    if os.path.isfile(FRONT):
        # The front page becomes the repository's README.md: its links resolve from the root.
        front_files = 1
        links += check_file(FRONT, pictures, used, "docs/src/pictures/", base_dir=REPO)
    unused = sorted(set(pictures) - used)
    if errors:
        print("\n".join(errors))
        print(f"FAILED: {len(errors)} problem(s)")
        return 1
    print(f"OK: {len(chapters)} chapter files and {front_files} front page, {links} links and pictures, "
          f"{len(pictures)} pictures listed in pictures.txt")
    for name in unused:
        print(f"note: {name} is listed in pictures.txt but no page shows it")
    return 0


if __name__ == "__main__":
    sys.exit(main())
