#!/usr/bin/env python3
"""Checks in an apitrace that no GL query result is read before the program asked whether it is
available and was told yes (issue 39, point 4: the window must never wait on a query).

    xvfb-run -a apitrace trace --api gl -o view.trace build/tallow view --preset candle \
        --size 160x90 --frames 12 --stats /tmp/view.json
    python3 scripts/check_query_reads.py view.trace

A query is issued by glBeginQuery/glEndQuery or glQueryCounter; a read (GL_QUERY_RESULT) of it is
counted as asked when, since it was last issued, a GL_QUERY_RESULT_AVAILABLE of the same id
returned 1. Prints the reads, the asked ones and each unasked read's call; exits 1 if any.
"""
import re
import subprocess
import sys

ISSUE = re.compile(r"^(\d+) gl(?:BeginQuery|BeginQueryIndexed|QueryCounter)\((?:target = \w+, )?(?:index = \d+, )?id = (\d+)")
AVAILABLE = re.compile(r"^(\d+) glGetQueryObject\w+\(id = (\d+), pname = GL_QUERY_RESULT_AVAILABLE, params = &(\d+)\)")
READ = re.compile(r"^(\d+) glGetQueryObject\w+\(id = (\d+), pname = GL_QUERY_RESULT, ")


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: check_query_reads.py TRACE", file=sys.stderr)
        return 2
    dump = subprocess.run(["apitrace", "dump", sys.argv[1]], capture_output=True, text=True, check=True).stdout
    told_yes = {}  # id -> True once asked and available since last issued
    reads = asked = 0
    unasked = []
    for line in dump.splitlines():
        if m := ISSUE.match(line):
            told_yes[m.group(2)] = False
        elif m := AVAILABLE.match(line):
            if m.group(3) != "0":
                told_yes[m.group(2)] = True
        elif m := READ.match(line):
            reads += 1
            if told_yes.get(m.group(2)):
                asked += 1
            else:
                unasked.append(line)
    print(f"query results read: {reads}, after an availability check that said yes: {asked}, without: {len(unasked)}")
    for line in unasked[:20]:
        print("  unasked:", line)
    return 1 if unasked else 0


if __name__ == "__main__":
    sys.exit(main())
