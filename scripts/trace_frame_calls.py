#!/usr/bin/env python3
"""Counts the GL calls of each frame of a headless capture, from an apitrace (issue 39, point 4).

    apitrace trace --api egl -o cap.trace build/tallow capture --gl egl --preset candle \
        --size 160x90 --frames 8 --fps 8 --time 10 --out /tmp/cap
    python3 scripts/trace_frame_calls.py cap.trace

A capture ends each frame by copying its targets into the read-back ring (gpu::AsyncReadback:
the pixel-pack buffer is unbound after the copies), so the trace is cut there: segment 0 is
start-up and the first frame, the last one the fetch of the last frame and the exit. Prints, per
segment, the calls that create or delete GL objects, read results or targets back (glGetTextureImage
counts a target copied into a buffer, glGetNamedBufferSubData a buffer fetched), or ask the driver
for state — what a steady frame should not do.
"""
import collections
import re
import subprocess
import sys

WATCHED = [
    "glCreateFramebuffers", "glDeleteFramebuffers", "glCreateBuffers", "glDeleteBuffers",
    "glCreateTextures", "glDeleteTextures", "glCreateQueries", "glDeleteQueries",
    "glCreateVertexArrays", "glDeleteVertexArrays", "glGenQueries", "glFenceSync", "glDeleteSync", "glGetIntegerv", "glGetInteger64v",
    "glGetTextureImage", "glGetTextureSubImage", "glReadPixels", "glGetNamedBufferSubData",
    "glGetQueryObjectui64v", "glGetQueryObjectiv", "glGetQueryObjectuiv", "glCheckNamedFramebufferStatus",
    "glClientWaitSync", "glFinish",
]


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: trace_frame_calls.py TRACE", file=sys.stderr)
        return 2
    try:
        dump = subprocess.run(["apitrace", "dump", "--color=never", sys.argv[1]], check=True,
                              capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"trace_frame_calls.py: apitrace dump {sys.argv[1]} failed: {e}", file=sys.stderr)
        return 1
    segments = [collections.Counter()]
    for line in dump.splitlines():
        m = re.match(r"\d+ (\w+)\(", line)
        if not m:
            continue
        segments[-1][m.group(1)] += 1
        if m.group(1) == "glBindBuffer" and "GL_PIXEL_PACK_BUFFER, buffer = 0)" in line:
            segments.append(collections.Counter())
    for i, calls in enumerate(segments):
        watched = ", ".join(f"{name} {calls[name]}" for name in WATCHED if calls[name])
        print(f"segment {i}: {sum(calls.values())} calls; {watched or 'none watched'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
