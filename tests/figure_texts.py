"""Checks that every figure under a folder carries a run's provenance (issue 31).

usage: python3 figure_texts.py DIR|FIGURE KEY=TEXT [KEY=TEXT ...]

Walks every .png and .pdf under DIR (or reads the one FIGURE), independently of indentmap's writer, a PNG's text chunks
(tEXt, zTXt, iTXt) and a PDF's information dictionary (its Subject, "key:\\nvalue" blocks, and its
Keywords, "key=value; ..."). Each KEY's value must contain TEXT. Prints one line per figure that lacks
one and exits 1 when any does, 2 when DIR holds no figure.
"""
import os
import re
import struct
import sys
import zlib


def png_texts(path):
    data = open(path, "rb").read()
    texts, at = {}, 8
    while at + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"tEXt":
            key, value = body.split(b"\0", 1)
            texts[key.decode("latin-1")] = value.decode("latin-1")
        elif kind == b"zTXt":
            key, value = body.split(b"\0", 1)
            texts[key.decode("latin-1")] = zlib.decompress(value[1:]).decode("latin-1")
        elif kind == b"iTXt":
            key, rest = body.split(b"\0", 1)
            compressed, rest = rest[0], rest[2:]
            _, _, value = rest.split(b"\0", 2)
            texts[key.decode("utf-8")] = (zlib.decompress(value) if compressed else value).decode("utf-8")
        at += 12 + length
    return texts


def pdf_string(data, name):
    """The information dictionary's entry name, a UTF-16 hex string or a literal one."""
    found = re.search(rb"/" + name + rb"\s*<FEFF([0-9A-Fa-f]*)>", data)
    if found:
        return bytes.fromhex(found.group(1).decode()).decode("utf-16-be")
    found = re.search(rb"/" + name + rb"\s*\(((?:\\.|[^\\)])*)\)", data)
    return found.group(1).decode("latin-1") if found else ""


def pdf_texts(path):
    data = open(path, "rb").read()
    texts = {}
    for block in pdf_string(data, b"Subject").split("\n\n"):
        key, _, value = block.strip("\n").partition(":\n")
        if value:
            texts[key] = value
    for pair in pdf_string(data, b"Keywords").split("; "):
        key, _, value = pair.partition("=")
        if value:
            texts[key] = value
    return texts


def main(folder, wanted):
    figures = [folder] if os.path.isfile(folder) else sorted(
        os.path.join(root, name) for root, _, names in os.walk(folder) for name in names
        if name.endswith((".png", ".pdf")))
    if not figures:
        print(f"{folder}: no figure")
        return 2
    missing = 0
    for figure in figures:
        texts = png_texts(figure) if figure.endswith(".png") else pdf_texts(figure)
        for key, text in wanted:
            if text not in texts.get(key, ""):
                print(f"{figure}: its {key!r} text lacks {text!r} (keys: {sorted(texts)})")
                missing += 1
    print(f"{len(figures)} figures, {missing} texts missing")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], [tuple(pair.split("=", 1)) for pair in sys.argv[2:]]))
