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
print("results scripts: ok")
