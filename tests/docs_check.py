#!/usr/bin/env python3
"""The documentation checked against the tree and the program, as a new user would follow it:

  (a) every relative link of README.md and docs/*.md names a file of the tree, and its #anchor a heading
      of that file (GitHub's anchors: lower case, punctuation dropped, spaces to hyphens, -1, -2 for repeats);
  (b) every option a documented command line gives (`indentmap COMMAND ... --option`, in code blocks and
      inline code) is one `indentmap COMMAND --help` lists;
  (c) every file of the tree a command or code span names (src/..., scripts/..., tests/...) exists
      ((b) and (c) not in docs/findings-recheck.md and docs/benchmarks.md: records of past days);
  (d) every `key = value` line of an INI block is a key of its [section] in the scene parser's table
      (src/scene/keys.c), and every key of that table is named in docs/scenes.md.

Usage: docs_check.py SOURCE_DIR INDENTMAP     exit 1 naming each fault (file:line and what was expected)
"""
import glob
import os
import re
import subprocess
import sys

LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*```")
OPTION = re.compile(r"(?<![\w-])(--[a-z][a-z0-9-]*)")
COMMAND = re.compile(r"\bindentmap\s+([a-z][a-z0-9-]*)(?:\s+(contact|height|animate|view3d)\b)?")
# prose names a command without the program: `indent --device auto`, `render view3d --ortho`
BARE_COMMAND = re.compile(r"^((?:surface|theory|indent|render|run|formats|info|mpi-indent)\b[^`]*?\s--)")
# a file of the tree a document names in code (src/NAME/, shaders/x.{vert,frag}, crash-* are patterns)
TREE_PATH = re.compile(r"(?<![\w./-])((?:src|tests|scripts|bench|include|python|examples|scenes|cmake|fuzz|shaders|docs)"
                       r"/[^\s`'\"(),;:]*)")
PATTERN = re.compile(r"[*<>{}\[]|(?<![A-Za-z])[A-Z]+(?![a-z])")
KEY_ENTRY = re.compile(r'\{"([a-z0-9_]+)",\s*"([a-z0-9_]+)"')
INI_SECTION = re.compile(r"^\s*\[([a-z0-9_]+)\]\s*(;.*)?$")
INI_KEY = re.compile(r"^\s*([a-z0-9_]+)\s*=")


# measurement records: their commands are those of the day they were measured
RECORDS = ("findings-recheck.md", "benchmarks.md")


def documents(source):
    return [os.path.join(source, "README.md")] + sorted(glob.glob(os.path.join(source, "docs", "*.md")))


def slug(heading):
    text = re.sub(r"[`*]|\[([^\]]*)\]\([^)]*\)", r"\1", heading).strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    seen = {}
    found = set()
    in_code = False
    with open(path, encoding="utf-8") as stream:
        for line in stream:
            if FENCE.match(line):
                in_code = not in_code
            match = None if in_code else HEADING.match(line)
            if match:
                base = slug(match.group(2))
                count = seen.get(base, 0)
                seen[base] = count + 1
                found.add(base if count == 0 else "%s-%d" % (base, count))
    return found


def lines_with_code(path):
    """Yields (line number, text, inside a fenced block) for every line of a markdown file."""
    in_code = False
    with open(path, encoding="utf-8") as stream:
        for number, line in enumerate(stream, 1):
            if FENCE.match(line):
                in_code = not in_code
                continue
            yield number, line.rstrip("\n"), in_code


def check_links(source, path, faults):
    for number, line, in_code in lines_with_code(path):
        if in_code:
            continue
        for target in LINK.findall(line):
            if re.match(r"^[a-z]+:", target):
                continue
            file_part, _, anchor = target.partition("#")
            linked = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            where = "%s:%d" % (os.path.relpath(path, source), number)
            if not os.path.exists(linked):
                faults.append("%s: link %s: no file %s" % (where, target, os.path.relpath(linked, source)))
            elif anchor and linked.endswith(".md") and anchor not in anchors(linked):
                faults.append("%s: link %s: %s has no heading with anchor #%s"
                              % (where, target, os.path.relpath(linked, source), anchor))


def help_options(program, command, cache):
    if command not in cache:
        result = subprocess.run([program] + command.split() + ["--help"], capture_output=True, text=True)
        cache[command] = set(OPTION.findall(result.stdout + result.stderr)) if result.returncode == 0 else None
    return cache[command]


def command_texts(path):
    """Yields (line number, text) for each command a markdown file shows: a code block's line (up to a
    comment; a line ending in a backslash joined to the next), and each inline code span (a span may
    run on over lines of its paragraph: the number is the line where it ends)."""
    joined, prose = "", ""
    for number, line, in_code in lines_with_code(path):
        if in_code:
            text = joined + " " + line.split("  #")[0]
            joined = text.rstrip("\\ ") if text.rstrip().endswith("\\") else ""
            if not joined:
                yield number, text
            continue
        if not line.strip():
            prose = ""
        prose += " " + line
        spans = prose.split("`")
        for span in spans[1:-1:2]:
            yield number, BARE_COMMAND.sub(r"indentmap \1", span)
        # an unclosed span runs on into the next line
        prose = "`" + spans[-1] if len(spans) % 2 == 0 else ""


def check_options(source, path, program, cache, faults):
    for number, text in command_texts(path):
        for match in COMMAND.finditer(text):
            command = " ".join(word for word in match.groups() if word)
            known = help_options(program, command, cache)
            if known is None:
                continue  # not a subcommand: prose such as "indentmap and ..."
            rest = text[match.end():]
            following = COMMAND.search(rest)
            for option in OPTION.findall(rest[:following.start()] if following else rest):
                if option not in known:
                    faults.append("%s:%d: indentmap %s: option %s is not in 'indentmap %s --help'"
                                  % (os.path.relpath(path, source), number, command, option, command))


def check_paths(source, path, faults):
    for number, text in command_texts(path):
        for named in TREE_PATH.findall(text):
            named = named.rstrip(".")
            if not os.path.exists(os.path.join(source, named)) and not PATTERN.search(named):
                faults.append("%s:%d: %s: no such file in the tree" % (os.path.relpath(path, source), number, named))


def scene_keys(source):
    with open(os.path.join(source, "src", "scene", "keys.c"), encoding="utf-8") as stream:
        return set(KEY_ENTRY.findall(stream.read()))


def check_scene_keys(source, path, keys, faults):
    section = None
    for number, line, in_code in lines_with_code(path):
        if not in_code:
            section = None
            continue
        heading = INI_SECTION.match(line)
        if heading:
            section = heading.group(1)
            continue
        key = INI_KEY.match(line)
        if section and key and (section, key.group(1)) not in keys:
            faults.append("%s:%d: [%s] %s is not a scene key (src/scene/keys.c)"
                          % (os.path.relpath(path, source), number, section, key.group(1)))


def check_keys_documented(source, keys, faults):
    with open(os.path.join(source, "docs", "scenes.md"), encoding="utf-8") as stream:
        text = stream.read()
    for section, key in sorted(keys):
        if not re.search(r"(?<![\w])%s(?![\w])" % re.escape(key), text):
            faults.append("docs/scenes.md: the scene key [%s] %s is not described" % (section, key))


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: docs_check.py SOURCE_DIR INDENTMAP\n")
        return 2
    source, program = argv[1], argv[2]
    faults = []
    keys = scene_keys(source)
    cache = {}
    for path in documents(source):
        check_links(source, path, faults)
        if os.path.basename(path) not in RECORDS:
            check_options(source, path, program, cache, faults)
            check_paths(source, path, faults)
        check_scene_keys(source, path, keys, faults)
    check_keys_documented(source, keys, faults)
    for fault in faults:
        print(fault)
    print("docs_check: %d documents, %d scene keys, %d fault(s)" % (len(documents(source)), len(keys), len(faults)))
    return 1 if faults else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
