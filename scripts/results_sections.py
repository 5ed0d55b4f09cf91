#!/usr/bin/env python3
"""Shared by the docs/RESULTS.md generators: put one generated section into RESULTS.md.

whole(path) says whether a run's output is complete (resume). splice(md, heading, lines) replaces the section that starts with `heading` (up to the next `## `)
or, when there is none, inserts it before the GPU section (`## On a GPU`) or at the end; the file is
written to MD.tmp and renamed, so it is whole or untouched. `append(md, lines)` adds at the end.
"""
import json
import os
import subprocess
import sys


def whole(path):
    """Whether a run's output may be kept on resume (TALLOW_RESULTS_RESUME=1): the file exists and,
    for a tallow JSON that says how its run ended (bench.json, stats.json: "run": {"state": ...}), the
    run completed. An interrupted bench or capture writes what it finished (docs/commands.md), which
    a resume must not take for the whole run."""
    if not os.path.exists(path):
        return False
    if not path.endswith(".json"):
        return True
    try:
        with open(path) as f:
            run = json.load(f).get("run")
    except (OSError, ValueError, AttributeError):
        return False
    return run is None or run.get("state") == "complete"


def run_dates(stats_list):
    """When the runs behind a section were made, from their stats.json provenance ("date", ISO UTC):
    " of 2026-12-03 08:41–09:00 UTC" (another day in full), or "" when none says. A section assembled
    from kept runs (TALLOW_RESULTS_RESUME) then says when it was measured, not only when it was written."""
    dates = sorted(st.get("provenance", {}).get("date", "") for st in stats_list)
    dates = [d.rstrip("Z").replace("T", " ")[:16] for d in dates if d]
    if not dates:
        return ""
    first, last = dates[0], dates[-1]
    if first == last:
        return " of %s UTC" % first
    return " of %s–%s UTC" % (first, last[11:] if last[:10] == first[:10] else last)


def pct(x):
    """A share as the tables print it: 0.0734 -> "7.3%" (None: a dash)."""
    return "—" if x is None else "%.1f%%" % (100.0 * x)


def fmt(x, d=3):
    """A number with d decimals (None: a dash)."""
    return "—" if x is None else "%.*f" % (d, x)


def rerun(script):
    """The closing line of a section written by scripts/<script> (run, then splice)."""
    return ("Rerun: `TALLOW=build/tallow python3 scripts/%s run DIR && python3 scripts/%s splice DIR docs/RESULTS.md`"
            " (or the whole `bash scripts/results.sh`)." % (script, script))


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


def run_once(cmd, out_file, quiet=False):
    """Runs cmd unless TALLOW_RESULTS_RESUME=1 and its output out_file is whole already."""
    if os.environ.get("TALLOW_RESULTS_RESUME") == "1" and whole(out_file):
        print("results: kept", out_file, flush=True)
        return
    print("results:", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL if quiet else None)


def main(args, doc, run, section, heading):
    """The generators' command line (args without the program): run DIR [--quick], report DIR MD,
    splice DIR MD; anything else prints `doc` and exits."""
    if len(args) >= 2 and args[0] == "run":
        run(args[1], "--quick" in args[2:])
    elif len(args) == 3 and args[0] == "report":
        append(args[2], section(args[1]))
    elif len(args) == 3 and args[0] == "splice":
        splice(args[2], heading, section(args[1]))
    else:
        sys.exit(doc)
