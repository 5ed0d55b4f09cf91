#!/usr/bin/env python3
"""Issue 16, point 7: the animated fields' frame times, the path before the fields moved to the GPU
(`field.evaluate=cpu`: each frame's lattice sampled on the CPU and uploaded) against the GPU path
(`field.evaluate=gpu`, the default), measured in one run; the docs/RESULTS.md section they become.

  results_fields.py run DIR [--quick]     runs the captures into DIR (TALLOW: the binary)
  results_fields.py report DIR MD         appends the section to MD
  results_fields.py splice DIR MD         replaces the section in MD (or adds it before the GPU
                                          section), leaving the rest of MD as it is

Called by scripts/results.sh (run, report). `splice` refreshes this one section of an existing
docs/RESULTS.md without the hours of the whole regeneration; the section names its own date. Every
number comes from the stats.json of `tallow capture` runs.
"""
import json
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_sections  # noqa: E402

FIELDS = ("candle", "blob")
RESOLUTIONS = (64, 128, 256)
EVALUATIONS = ("cpu", "gpu")
SIZE = "320x180"
FPS = 4  # the candle's burn and the blob's motion both change visibly between frames
HEADING = "## Animated fields: frame time before and after the GPU fields (issue 16, point 7)"
SOFTWARE = ("llvmpipe", "softpipe", "swrast", "lavapipe")
WALL_OVER_GPU_BOUND = 1.3  # issue 16: the animated candle's wall time within 1.3x of its GPU time
SAMPLE_CPU_BOUND_MS = 5.0  # issue 16: the geometry's CPU work per animated frame at 128^3


def frames_for(quick):
    return 3 if quick else 6


def run_dir(work, field, res, evaluate):
    return os.path.join(work, "%s_%d_%s" % (field, res, evaluate))


def run(work, quick):
    os.makedirs(work, exist_ok=True)
    binary = os.environ.get("TALLOW", "tallow")
    resolutions = (32, 64) if quick else RESOLUTIONS
    for field in FIELDS:
        for res in resolutions:
            for evaluate in EVALUATIONS:
                out = run_dir(work, field, res, evaluate)
                if os.environ.get("TALLOW_RESULTS_RESUME") == "1" and results_sections.whole(os.path.join(out, "stats.json")):
                    print("results: kept", out, flush=True)
                    continue
                cmd = [binary, "capture", "--preset", field, "--size", "96x54" if quick else SIZE,
                       "--frames", str(frames_for(quick)), "--fps", str(FPS), "--out", out,
                       "--set", "field.res=%d" % res, "--set", "field.evaluate=%s" % evaluate]
                print("results:", " ".join(cmd), flush=True)
                subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def measure(stats):
    """Medians over the frames after the first (the first builds programs and buffers)."""
    frames = stats["frames"][1:] or stats["frames"]

    def per_frame(key, name=None):
        out = []
        for f in frames:
            v = f.get(key)
            if name is not None:
                v = (v or {}).get(name)
            out.append(v)
        return median(out)

    sample_thread = per_frame("thread_cpu_ms", "field.sample")
    extract_thread = per_frame("thread_cpu_ms", "field.extract")
    return {
        "frames": len(frames),
        "wall": per_frame("wall_ms"),
        "gpu": per_frame("gpu_total_ms"),
        "sample_cpu": per_frame("cpu_ms", "field.sample"),
        "sample_thread": sample_thread,
        "sample_gpu": per_frame("gpu_ms", "field.sample"),
        "extract_gpu": per_frame("gpu_ms", "field.extract"),
        "extract_thread": extract_thread,
        "triangles": stats.get("triangles"),
        "time_from": frames[0]["time_s"],
        "time_to": frames[-1]["time_s"],
    }


def fmt(x, d=1):
    return "—" if x is None else "%.*f" % (d, x)


def section(work):
    rows = {}
    gl = None
    resolutions = []
    runs = []
    for field in FIELDS:
        for res in RESOLUTIONS + (32,):
            for evaluate in EVALUATIONS:
                path = os.path.join(run_dir(work, field, res, evaluate), "stats.json")
                if not os.path.exists(path):
                    continue
                with open(path) as f:
                    stats = json.load(f)
                runs.append(stats)
                gl = gl or stats["gl"]
                rows[(field, res, evaluate)] = measure(stats)
                if res not in resolutions:
                    resolutions.append(res)
    resolutions.sort()
    lines = []
    add = lines.append
    add(HEADING)
    add("")
    renderer = gl.get("GL_RENDERER", "?") if gl else "?"
    add(results_sections.generated_line("results_fields.py", "`tallow capture`", runs))
    add("Device: `%s` (%s); CPU threads visible: %s." % (renderer, gl.get("GL_VERSION", "?") if gl else "?",
                                                       os.cpu_count()))
    add("")
    if any(s in renderer.lower() for s in SOFTWARE):
        add("**A software rasteriser**: its \"GPU\" is this CPU, so these are not GPU frame rates; they show where a")
        add("frame's time goes and whether a frame waits on the CPU's own work.")
        add("")
    add("Each row is `tallow capture --preset FIELD --size %s --fps %d --set field.res=RES --set field.evaluate=E`," % (SIZE, FPS))
    add("every frame at a new time (the field changes every frame); medians over the frames after the first. `cpu`")
    add("is the path before the fields moved to the GPU, kept as `field.evaluate=cpu`: the lattice is sampled on")
    add("the CPU (the same closed-form lines in double) and uploaded each frame. `gpu` fills it by a compute")
    add("shader from uniforms at t. *wall*: the frame on the CPU clock up to `glFinish`; *GPU*: the sum of the")
    add("passes' timestamp spans; `field.sample` *clock* is the CPU clock around the pass (on llvmpipe it")
    add("includes the compute shader, which runs on the driver's threads while the caller waits), *thread* is")
    add("the rendering thread's own CPU time in it (`thread_cpu_ms`): Tallow's work and the driver's on that")
    add("thread, which is what a real GPU would leave on the CPU.")
    add("")
    add("The path at the time issue 16 was filed rebuilt the candle's OpenVDB level set on the CPU every frame")
    add("(2.9–3.9 s of wall time per frame against 0.5–0.9 s of GPU time at 96×54). That code is gone: the candle")
    add("is now one closed form (`shaders/fields/candle.glsl`), and `cpu` evaluates the same lines on the CPU, so")
    add("the before measured here is already far cheaper than the one the issue measured.")
    add("")
    add("| field | res | evaluate | frames | wall [ms] | GPU [ms] | wall / GPU | field.sample clock / thread / GPU [ms] | field.extract GPU [ms] | triangles |")
    add("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    for field in FIELDS:
        for res in resolutions:
            for evaluate in EVALUATIONS:
                r = rows.get((field, res, evaluate))
                if r is None:
                    continue
                ratio = r["wall"] / r["gpu"] if r["wall"] and r["gpu"] else None
                add("| %s | %d³ | %s | %d | %s | %s | %s | %s / %s / %s | %s | %s |" % (
                    field, res, evaluate, r["frames"], fmt(r["wall"]), fmt(r["gpu"]), fmt(ratio, 3),
                    fmt(r["sample_cpu"]), fmt(r["sample_thread"], 2), fmt(r["sample_gpu"]), fmt(r["extract_gpu"]),
                    r["triangles"] if r["triangles"] is not None else "—"))
    add("")
    add("Against the issue's targets, from the rows above:")
    add("")
    for field in FIELDS:
        for res in resolutions:
            cpu, gpu = rows.get((field, res, "cpu")), rows.get((field, res, "gpu"))
            if not cpu or not gpu:
                continue
            ratio = gpu["wall"] / gpu["gpu"] if gpu["gpu"] else None
            verdict = "—" if ratio is None else ("within" if ratio <= WALL_OVER_GPU_BOUND else "**over**")
            add("- %s, %d³: wall %s (cpu) → %s ms (gpu) per frame, cpu / gpu = %s; wall / GPU %s → %s, %s the bound of %.1f;"
                " field.sample thread CPU %s → %s ms%s." % (
                    field, res, fmt(cpu["wall"]), fmt(gpu["wall"]),
                    fmt(cpu["wall"] / gpu["wall"], 2) if gpu["wall"] else "—",
                    fmt(cpu["wall"] / cpu["gpu"], 3) if cpu["gpu"] else "—", fmt(ratio, 3), verdict,
                    WALL_OVER_GPU_BOUND, fmt(cpu["sample_thread"], 2), fmt(gpu["sample_thread"], 3),
                    "" if res != 128 else (" (bound %.0f ms: %s)" % (
                        SAMPLE_CPU_BOUND_MS,
                        "under" if gpu["sample_thread"] is not None and gpu["sample_thread"] < SAMPLE_CPU_BOUND_MS
                        else "**not under**"))))
    add("")
    add(results_sections.rerun("results_fields.py"))
    add("")
    return lines


def report(work, md):
    results_sections.append(md, section(work))


def splice(work, md):
    """Replaces this section of MD, or inserts it before the GPU section (results_sections.splice)."""
    results_sections.splice(md, HEADING, section(work))


def main(argv):
    if len(argv) >= 2 and argv[0] == "run":
        run(argv[1], "--quick" in argv[2:])
    elif len(argv) == 3 and argv[0] == "report":
        report(argv[1], argv[2])
    elif len(argv) == 3 and argv[0] == "splice":
        splice(argv[1], argv[2])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
