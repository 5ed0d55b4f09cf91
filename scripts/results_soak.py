#!/usr/bin/env python3
"""Issue 37, point 6: a long capture writes O(frames) bytes, and its time and memory per frame stay
flat. 10 000 tiny frames (the slab at 8x8, method=albedo: rendering costs next to nothing, so what
is measured is the writing) with the bytes the process wrote as the kernel counts them (wchar of
/proc/PID/io, read after the exit and before the process is reaped), the bytes it kept, the time
between consecutive frames (their PNGs' modification times: rendering, read-back, the PNG and EXR,
the frame's stats line) and the resident memory after each frame (stats.json's rss_bytes), early in
the run against late; the docs/RESULTS.md section they become.

  results_soak.py run DIR [--quick]     captures into DIR (TALLOW: the binary); --quick: 1000 frames
  results_soak.py report DIR MD         appends the section to MD
  results_soak.py splice DIR MD         replaces the section in MD (or adds it before the GPU section)

Called by scripts/results.sh (run, report).
"""
import json
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_sections  # noqa: E402
from results_sections import fmt  # noqa: E402

HEADING = "## Long captures: bytes, time and memory per frame (issue 37, point 6)"
FRAMES = 10000
WINDOW = 1000  # frames compared at the start and at the end


def capture_args(out, frames):
    return ["capture", "--preset", "slab", "--size", "8x8", "--set", "method=albedo", "--set", "render.shadows=false",
            "--frames", str(frames), "--out", out]


def run(work, quick):
    os.makedirs(work, exist_ok=True)
    out, record = os.path.join(work, "soak"), os.path.join(work, "soak_io.json")
    frames = WINDOW if quick else FRAMES
    if os.environ.get("TALLOW_RESULTS_RESUME") == "1" and results_sections.whole(os.path.join(out, "stats.json")) \
            and os.path.exists(record):
        print("results: kept", out, flush=True)
        return
    tallow = os.environ.get("TALLOW", "build/tallow")
    args = capture_args(out, frames)
    print("results:", tallow, " ".join(args), flush=True)
    start = time.monotonic()
    pid = os.fork()
    if pid == 0:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 1)
        os.execv(tallow, [tallow] + args)
    # The exit without reaping (WNOWAIT): the zombie's /proc entry still holds its I/O counts.
    os.waitid(os.P_PID, pid, os.WEXITED | os.WNOWAIT)
    with open("/proc/%d/io" % pid) as f:
        io = dict(line.split(":") for line in f.read().split("\n") if ":" in line)
    _, status = os.waitpid(pid, 0)
    if status != 0:
        sys.exit("results_soak: the capture failed (status %d)" % status)
    kept = sum(os.path.getsize(os.path.join(out, name)) for name in os.listdir(out))
    with open(record + ".tmp", "w") as f:
        json.dump({"frames": frames, "wchar": int(io["wchar"]), "kept_bytes": kept,
                   "seconds": time.monotonic() - start}, f)
    os.replace(record + ".tmp", record)


def section(work):
    out = os.path.join(work, "soak")
    with open(os.path.join(work, "soak_io.json")) as f:
        io = json.load(f)
    with open(os.path.join(out, "stats.json")) as f:
        stats = json.load(f)
    frames = stats["frames"]
    n = len(frames)
    window = min(WINDOW, n // 2)
    # Each frame's PNG is renamed onto its name when written: the time between two of them is what one
    # frame costs, end to end.
    stamps = [os.stat(os.path.join(out, "frame_%04d.png" % i)).st_mtime_ns / 1e6 for i in range(n)]
    gaps = [b - a for a, b in zip(stamps, stamps[1:])]
    early, late = gaps[:window - 1], gaps[-(window - 1):]
    wall_early = statistics.median(f["wall_ms"] for f in frames[:window])
    wall_late = statistics.median(f["wall_ms"] for f in frames[-window:])
    rss = [f["rss_bytes"] for f in frames]
    mib = 1024.0 * 1024.0
    written, kept = io["wchar"], io["kept_bytes"]
    lines = [HEADING, ""]
    lines.append(results_sections.generated_line("results_soak.py", "`tallow capture`", [stats]))
    lines.append("")
    lines.append("The slab at 8×8 with `method=albedo` and no shadows, %d frames: rendering costs next to nothing, so"
                 " the run measures what a frame costs to write. Each frame's record is one line appended to"
                 " `stats.frames.jsonl` and `stats.json` is rewritten at most once a second (before, it was rewritten"
                 " whole after every frame: the issue measured 251 MiB written for 600 frames that kept 1.6 MiB, and"
                 " 5 → 42 ms a frame outside rendering over 1000 frames)." % n)
    lines.append("")
    lines.append("| | value |")
    lines.append("|---|---:|")
    lines.append("| bytes written (kernel's count, all writes) | %s MiB |" % fmt(written / mib, 2))
    lines.append("| bytes kept (frames and stats.json) | %s MiB |" % fmt(kept / mib, 2))
    lines.append("| written / kept | %s (the issue's bound: 3 × kept + 8 MiB = %s MiB) |"
                 % (fmt(written / kept, 2), fmt((3 * kept + 8 * mib) / mib, 1)))
    lines.append("| time between frames, median of the first %d | %s ms |" % (window, fmt(statistics.median(early), 3)))
    lines.append("| time between frames, median of the last %d | %s ms |" % (window, fmt(statistics.median(late), 3)))
    lines.append("| rendering (wall_ms), median of the first / last %d | %s / %s ms |"
                 % (window, fmt(wall_early, 3), fmt(wall_late, 3)))
    lines.append("| resident memory after frame %d / %d / %d | %s / %s / %s MiB |"
                 % (window, n // 2, n, fmt(rss[window - 1] / mib, 1), fmt(rss[n // 2 - 1] / mib, 1), fmt(rss[-1] / mib, 1)))
    lines.append("| whole run | %s s |" % fmt(io["seconds"], 1))
    lines.append("")
    lines.append("Device: `%s`; the times are on a shared 2-core machine, so they are noisy; what matters is that"
                 " the late frames cost what the early ones did." % stats["gl"]["GL_RENDERER"])
    lines.append("")
    lines.append(results_sections.rerun("results_soak.py"))
    lines.append("")
    return lines


if __name__ == "__main__":
    results_sections.main(sys.argv[1:], __doc__, run, section, HEADING)
