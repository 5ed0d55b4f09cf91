#!/usr/bin/env python3
"""Shared by the docs/RESULTS.md generators: put one generated section into RESULTS.md.

splice(md, heading, lines) replaces the section that starts with `heading` (up to the next `## `)
or, when there is none, inserts it before the GPU section (`## On a GPU`) or at the end; the file is
written to MD.tmp and renamed, so it is whole or untouched. `append(md, lines)` adds at the end.
"""
import os


def splice(md, heading, lines):
    with open(md) as f:
        text = f.read().split("\n")
    if heading in text:
        start = text.index(heading)
        end = next((i for i in range(start + 1, len(text)) if text[i].startswith("## ")), len(text))
    else:
        start = next((i for i, line in enumerate(text) if line.startswith("## On a GPU")), len(text))
        end = start
    out = text[:start] + lines + text[end:]
    with open(md + ".tmp", "w") as f:
        f.write("\n".join(out))
    os.replace(md + ".tmp", md)


def append(md, lines):
    with open(md, "a") as f:
        f.write("\n".join(lines) + "\n")
