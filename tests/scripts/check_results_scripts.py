#!/usr/bin/env python3
"""The RESULTS generators (scripts/*.py) compile, and the GPU section (issue 18) says that no GPU
figures exist when no device-bench run was copied in, and includes the run's report when one was.
Standard library only; run by ctest (ResultsScripts.*)."""
import json
import os
import py_compile
import sys
import tempfile

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
scripts = os.path.join(root, "scripts")
for name in sorted(os.listdir(scripts)):
    if name.endswith(".py"):
        py_compile.compile(os.path.join(scripts, name), doraise=True)

sys.path.insert(0, scripts)
import results_bench  # noqa: E402
import results_sections  # noqa: E402

# Resume keeps only whole runs: an interrupted bench or capture writes the rows or frames it
# finished, with "run": {"state": "interrupted"}, and must run again.
with tempfile.TemporaryDirectory() as tmp:
    def written(name, content):
        path = os.path.join(tmp, name)
        with open(path, "w") as f:
            f.write(content)
        return path
    assert not results_sections.whole(os.path.join(tmp, "absent.json"))
    assert results_sections.whole(written("bench.json", json.dumps({"run": {"state": "complete"}, "rows": []})))
    assert not results_sections.whole(written("cut.json", json.dumps({"run": {"state": "interrupted"}})))
    assert not results_sections.whole(written("torn.json", '{"run": {"sta'))
    assert results_sections.whole(written("ref.exr", "EXR"))
    assert results_sections.whole(written("placement.json", json.dumps({"shapes": []})))

with tempfile.TemporaryDirectory() as tmp:
    md = os.path.join(tmp, "RESULTS.md")
    with open(md, "w") as f:
        f.write("# Results\n")
    results_bench.report_gpu(os.path.join(tmp, "gpu"), md)  # no run copied in
    text = open(md).read()
    assert text.startswith("# Results\n"), "the section is appended"
    assert "**No GPU figures exist yet" in text, text

    # A run from a GPU: its report, headings two levels down, under a line naming the device.
    gpu = os.path.join(tmp, "gpu")
    os.makedirs(gpu)
    with open(os.path.join(gpu, "results.json"), "w") as f:
        json.dump({"device": {"GL_RENDERER": "NVIDIA H200/PCIe/SSE2", "GL_VERSION": "4.6.0",
                              "nvidia_smi_name": "NVIDIA H200", "software": False},
                   "meta": {"mode": "full"}, "bundle": {"commit": "abc1234"}}, f)
    with open(os.path.join(gpu, "results.md"), "w") as f:
        f.write("# Device bench\n\n| row | fps |\n|---|---|\n| candle | 42 |\n")
    with open(md, "w") as f:
        f.write("# Results\n")
    results_bench.report_gpu(gpu, md)
    text = open(md).read()
    assert "No GPU figures" not in text, text
    assert "Measured on **NVIDIA H200**" in text, text
    assert "\n### Device bench\n" in text and "| candle | 42 |" in text, text

# Issue 16's fields section: medians over the frames after the first, the wall / GPU ratio against
# its bound, and `splice` replacing the section in place (never twice) before the GPU section.
import results_fields  # noqa: E402

with tempfile.TemporaryDirectory() as tmp:
    def stats(walls, gpus, sample_thread):
        frames = [{"time_s": 12 + 0.25 * i, "wall_ms": w, "gpu_total_ms": g,
                   "cpu_ms": {"field.sample": 1.0}, "thread_cpu_ms": {"field.sample": st, "field.extract": 0.5},
                   "gpu_ms": {"field.sample": 0.1, "field.extract": 2.0}}
                  for i, (w, g, st) in enumerate(zip(walls, gpus, sample_thread))]
        return {"gl": {"GL_RENDERER": "llvmpipe (test)", "GL_VERSION": "4.5"}, "triangles": 1000, "frames": frames}
    for evaluate, walls, gpus, st in (("cpu", [900, 200, 300, 250], [50, 100, 100, 100], [9, 80, 90, 70]),
                                      ("gpu", [900, 120, 130, 125], [50, 100, 100, 100], [9, 0.2, 0.4, 0.3])):
        d = results_fields.run_dir(tmp, "candle", 128, evaluate)
        os.makedirs(d)
        with open(os.path.join(d, "stats.json"), "w") as f:
            json.dump(stats(walls, gpus, st), f)
    md = os.path.join(tmp, "RESULTS.md")
    with open(md, "w") as f:
        f.write("# Results\n\n## Earlier\n\ntext\n\n## On a GPU (issue 18)\n\nnone\n")
    results_fields.splice(tmp, md)
    results_fields.splice(tmp, md)
    text = open(md).read()
    assert text.count(results_fields.HEADING) == 1, text
    assert text.index("## Earlier") < text.index(results_fields.HEADING) < text.index("## On a GPU"), text
    # cpu: wall median of 200, 300, 250 = 250, GPU 100 -> 2.500, over 1.3; gpu: 125 / 100 = 1.250, within.
    assert "| candle | 128³ | cpu | 3 | 250.0 | 100.0 | 2.500 |" in text, text
    assert "| candle | 128³ | gpu | 3 | 125.0 | 100.0 | 1.250 |" in text, text
    assert "cpu / gpu = 2.00; wall / GPU 2.500 → 1.250, within the bound of 1.3" in text, text
    assert "field.sample thread CPU 80.00 → 0.300 ms (bound 5 ms: under)" in text, text
# Issues 17 and 35's animated-candle section: medians over the frames (wall: after the first), the K
# per frame, and the verdicts from hand-made numbers.
import results_animated  # noqa: E402

with tempfile.TemporaryDirectory() as tmp:
    def row(name, samples, maps, walls, rels, lowers, fireflies, extra=()):
        d = results_animated.row_dir(tmp, name)
        os.makedirs(d)
        frames = [{"time_s": 16 + i / 8, "wall_ms": w, "sss": {"maps": maps}} for i, w in enumerate(walls)]
        with open(os.path.join(d, "stats.json"), "w") as f:
            json.dump({"gl": {"GL_RENDERER": "llvmpipe (test)"}, "parameters": {"sss.samples": samples},
                       "frames": frames}, f)
        for i, (rel, lower, ff) in enumerate(zip(rels, lowers, fireflies)):
            listed = [e for frame, e in extra if frame == i]
            with open(os.path.join(d, "error_%04d.json" % i), "w") as f:
                json.dump({"error": {"rel_rmse": rel, "upper_mean_ratio": 1.0, "lower_mean_ratio": lower,
                                     "fireflies": ff, "reference_fireflies": 4, "pixels": 3000,
                                     "fireflies_not_in_reference": listed}}, f)
    # The defaults' extra fireflies: one pixel in frames 1 and 2 (a feature at the reference's threshold),
    # another in frame 2 only (noise, the reference near its median there).
    feature = lambda over, ref: {"x": 181, "y": 133, "channel": 2, "over_median": 4.2, "reference_over_median": ref,
                                 "over_reference": over}
    extra = [(1, feature(1.09, 3.86)), (2, feature(1.1, 3.95)),
             (2, {"x": 5, "y": 6, "channel": 0, "over_median": 9.0, "reference_over_median": 1.2, "over_reference": 7.5})]
    row("K = 16", 8, 16, [5000, 4000, 4000, 4000], [0.10, 0.10, 0.10, 0.10], [0.97] * 4, [0] * 4)
    row("restart (sss.history = 0)", 8, 8, [5000, 1800, 1800, 1800], [0.18] * 4, [1.01] * 4, [0] * 4)
    row("defaults", 8, 8, [5000, 2000, 2100, 1900], [0.12, 0.11, 0.13, 0.12], [0.97, 0.96, 0.98, 0.97], [0, 0, 5, 1],
        extra)
    text = "\n".join(results_animated.section(tmp))
    # defaults: rel median of 0.11, 0.12, 0.12, 0.13 = 0.12; lower 0.97; fireflies median of 0, 0, 1, 5 = 0.5;
    # wall median of 2000, 2100, 1900 = 2000 (the first frame left out).
    assert "| defaults | 8 | 8 | 12.0% | 1.000 / 0.970 | 0.5 (4) | 2000 |" in text, text
    assert "| K = 16 | 8 | 16 | 10.0% | 1.000 / 0.970 | 0 (4) | 4000 |" in text, text
    assert "Lower-wall bias within 5% of the reference (issue 17): 0.970 with the defaults (met)." in text, text
    assert "0.5 against 4 with the defaults (met)" in text, text
    assert ("relative RMSE 12.0% with the defaults against 18.0% restarting at every frame (1.50×), lower wall 0.970"
            " against 1.010, at 2000 against 1800 ms a frame") in text, text
    assert "t = 16 s" in text and "for 4 frames (to 16.375 s)" in text, text
    # By pixel, the one seen in more frames first; ranges over its frames.
    assert ("  - defaults, pixel (181, 133), blue, frame(s) 1, 2 (K 8, 8): 1.09–1.10× the reference there; the"
            " reference's own ratio to its 5×5 median there 3.86–3.95 (a firefly above 4).") in text, text
    assert ("  - defaults, pixel (5, 6), red, frame(s) 2 (K 8): 7.50× the reference there; the reference's own ratio"
            " to its 5×5 median there 1.20 (a firefly above 4).") in text, text
    assert text.index("pixel (181, 133)") < text.index("pixel (5, 6)") < text.index("The maps kept"), text
# Issue 17, point 3's verdict: wins counted per sss.history_rescale against the restart of the same
# preset, rate and N (hand-made rows), and the defaults' rows (8 frames, move 0.5, N = 8, rescale 1)
# judged on their own: they must win in most animations.
import results_history  # noqa: E402

def hrow(fps, samples, history, rel, rescale=1.0, preset="blob"):
    return {"preset": preset, "fps": fps, "samples": samples, "history": history, "rel_rmse": rel, "move": 0.5,
            "rescale": rescale}
hrows = [hrow(8, 8, 0, 0.05), hrow(8, 8, 8, 0.10, 0.0), hrow(8, 8, 8, 0.04), hrow(30, 1, 0, 0.17),
         hrow(30, 1, 8, 0.15), hrow(30, 1, 4, 0.18), hrow(4, 8, 0, 0.076, preset="candle"),
         hrow(4, 8, 8, 0.055, preset="candle")]
pairs = [(r, results_history.restart_of(hrows, r)) for r in hrows if r["history"] > 0]
assert [b["rel_rmse"] for _, b in pairs] == [0.05, 0.05, 0.17, 0.17, 0.076], pairs
text = "\n".join(results_history.verdict(pairs))
assert "with `sss.history_rescale` = 0 in 0 of 1; with `sss.history_rescale` = 1 in 3 of 4" in text, text
assert "blob at 8 fps 4.0% against 5.0%, candle at 4 fps 5.5% against 7.6%; they win in 2 of 2" in text, text
assert "so the maps are not restarted by default" in text, text
# Losing in one of two: no majority, so the verdict says the default should be a restart.
text = "\n".join(results_history.verdict([(hrow(8, 8, 8, 0.06), hrow(8, 8, 0, 0.05)), pairs[4]]))
assert "do not win in most animations" in text, text
# A section's runs' dates from their provenance: one day, across midnight, none, one run.
dated = lambda *ds: [{"provenance": {"date": d}} for d in ds]
assert results_sections.run_dates(dated("2026-12-03T09:00:02Z", "2026-12-03T08:41:57Z")) == " of 2026-12-03 08:41–09:00 UTC"
assert (results_sections.run_dates(dated("2026-12-02T23:41:57Z", "2026-12-03T00:10:02Z"))
        == " of 2026-12-02 23:41–2026-12-03 00:10 UTC")
assert results_sections.run_dates([{}, {"provenance": {}}]) == ""
assert results_sections.run_dates(dated("2026-12-03T08:41:57Z")) == " of 2026-12-03 08:41 UTC"
print("results scripts: ok")

# The cost model (scripts/cost_model.py) on numbers worked by hand: llvmpipe of 2 cores × 8 lanes at
# 2 GHz does 32 000 lane-cycles a microsecond; a pure compute pass of 1000 invocations in 1 ms costs
# 32 000 lane-cycles each, a pure raster pass of 4000 in 2 ms 16 000. A mixed pass (sss.maps: its
# raster at sss.light_gbuffer's cost) of 1000 raster and 500 compute invocations in 3 ms: raster
# 1000 × 16 000, compute the rest, (96 000 000 − 16 000 000) / 500 = 160 000. On an H200 compute
# has 132 × 128 lanes, raster 4 × 128, at 1.98 GHz.
import cost_model  # noqa: E402
def pass_counts(raster, compute):
    return {"vertex": 0, "geometry": 0, "fragment": raster, "compute": compute}
data = {"path": "synthetic", "renderer": "llvmpipe (LLVM 15.0.6, 256 bits)",
        "counts": {"camera.still": pass_counts(0, 1000), "sss.light_gbuffer": pass_counts(4000, 0),
                   "sss.maps": pass_counts(1000, 500)},
        "ms": {"camera.still": 1.0, "sss.light_gbuffer": 2.0, "sss.maps": 3.0}, "steady_frames": [2]}
cal = cost_model.calibrate(data, 2, 2.0)
assert abs(cal["c"]["camera.still"]["compute"] - 32000.0) < 1e-6, cal
assert abs(cal["c"]["sss.light_gbuffer"]["raster"] - 16000.0) < 1e-6, cal
assert abs(cal["c"]["sss.maps"]["raster"] - 16000.0) < 1e-6 and abs(cal["c"]["sss.maps"]["compute"] - 160000.0) < 1e-6, cal
h200 = cost_model.project(cal, data, "h200")
ms = {r["pass"]: r["ms"] for r in h200["passes"]}
lane_ms = 1.98e6  # cycles a lane runs in a millisecond
assert abs(ms["camera.still"] - 1000 * 32000 / (132 * 128 * lane_ms)) < 1e-12, ms
assert abs(ms["sss.light_gbuffer"] - 4000 * 16000 / (4 * 128 * lane_ms)) < 1e-12, ms
assert abs(ms["sss.maps"] - (1000 * 16000 / (4 * 128 * lane_ms) + 500 * 160000 / (132 * 128 * lane_ms))) < 1e-12, ms
# The check on llvmpipe predicts a capture's own times back exactly.
assert abs(cost_model.check(cal, data)["relative_error"]) < 1e-12
print("cost model: ok")
