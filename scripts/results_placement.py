#!/usr/bin/env python3
"""Issue 16, point 4: the docs/RESULTS.md section on dual contouring's vertex placement.

  results_placement.py PLACEMENT.json MD          appends the section to MD
  results_placement.py splice PLACEMENT.json MD   replaces it in MD (or adds it before the GPU section)

PLACEMENT.json is what `tallow probe placement` writes (scripts/results.sh runs it); every number in
the section comes from it, and so does the verdict (which placement is closer to the exact surface,
on the sharp and on the smooth shapes).
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_sections  # noqa: E402

SOFTWARE = ("llvmpipe", "softpipe", "swrast", "lavapipe")


def fmt(x, d=3):
    return "—" if x is None else "%.*f" % (d, x)


def geomean(values):
    values = [v for v in values if v is not None and v > 0]
    return math.exp(sum(math.log(v) for v in values) / len(values)) if values else None


def section(r):
    lines = []
    add = lines.append
    gpu = r["gpu"]
    add("## Dual contouring's vertex placement (issue 16, point 4)")
    add("")
    add("`field.placement`: `mass` puts each surface patch's vertex at the mean of its cell's edge crossings")
    add("(surface nets); `qef` at the minimum of the squared distances to the tangent planes at those crossings")
    add("(normals from the lattice alone: along the edge its own difference, across it a central difference, or a")
    add("one-sided one where the central stencil straddles a crease), regularised toward the mass point as a")
    add("probabilistic quadric (Trettner and Kobbelt 2020), kept inside the cell and within half a cell of the")
    add("lattice's own (trilinear) surface")
    add("(`shaders/dual_contouring/qef.glsl`). Each shape is sampled on the lattice, extracted on the GPU with")
    add("both placements, and compared with its exact surface. Distances are in cells of the lattice:")
    add("mesh → surface at every triangle's vertices, edge midpoints and centroid (mean weighted by area),")
    add("surface → mesh at samples of the exact surface; **H** is the symmetric Hausdorff distance, the larger")
    add("of the two maxima. The cube and the sphere are exact signed distances (surface samples 0.2 cells")
    add("apart); the blob's and the candle's surface is their field's zero set, stood for by OpenVDB's mesh of")
    add("a 256³ lattice with every vertex moved onto it by Newton steps. The candle is at t = 0, its rim not")
    add("yet melted, its wick (1 mm radius, under a cell) left out of both directions. Checks: edges not in")
    add("exactly two triangles (watertight, manifold), zero-area triangles, triangles wound against the")
    add("field's gradient.")
    add("")
    add("Device: `%s` (%s), OpenGL context `%s`. Extraction times are medians of %d GL timestamp spans after"
        % (gpu["GL_RENDERER"], gpu["GL_VERSION"], gpu["backend"], r["repeats"]))
    add("one warm-up, for the placement's cost only (the same lattice, the same four passes).")
    if any(s in gpu["GL_RENDERER"].lower() for s in SOFTWARE):
        add("**A software rasteriser: the times only compare the two placements on this CPU.**")
    add("")
    ratios = {"sharp": [], "smooth": []}
    means = {"sharp": [], "smooth": []}
    costs = []
    wins = {"sharp": [0, 0], "smooth": [0, 0]}  # QEF lower, cases
    for shape in r["shapes"]:
        kind = "sharp" if shape["sharp"] else "smooth"
        add("### %s (%s features)" % (shape["shape"], kind))
        add("")
        add("%s. Reference: %s." % (shape["description"][0].upper() + shape["description"][1:], shape["reference"]))
        add("")
        add("| res | placement | H | mesh → surface max / mean | surface → mesh max / mean | triangles | bad edges / zero-area / against ∇ | extract [ms] |")
        add("|---:|---|---:|---:|---:|---:|---:|---:|")
        for row in shape["rows"]:
            for p in ("mass", "qef"):
                m = row[p]
                add("| %d³ | %s | %s | %s / %s | %s / %s | %d | %d / %d / %d | %s |" % (
                    row["res"], p, fmt(m["hausdorff_cells"]), fmt(m["mesh_to_surface_max_cells"]),
                    fmt(m["mesh_to_surface_mean_cells"], 4), fmt(m["surface_to_mesh_max_cells"]),
                    fmt(m["surface_to_mesh_mean_cells"], 4), m["triangles"], m["bad_edges"],
                    m["zero_area_triangles"], m["against_gradient"], fmt(m["gpu_extract_ms"], 2)))
            q = row["qef_over_mass"]
            ratios[kind].append(q["hausdorff"])
            means[kind] += [q["mesh_to_surface_mean"], q["surface_to_mesh_mean"]]
            costs.append(q["gpu_extract"])
            wins[kind][1] += 1
            wins[kind][0] += 1 if row["qef"]["hausdorff_cells"] < row["mass"]["hausdorff_cells"] else 0
        add("")
    add("### Verdict")
    add("")
    for kind in ("sharp", "smooth"):
        g = geomean(ratios[kind])
        if g is None:
            continue
        add("- %s shapes: QEF's Hausdorff distance is %s× the mass point's (geometric mean over %d cases), lower in"
            " %d of %d; its mean distances (both directions) %s× the mass point's."
            % (kind.capitalize(), fmt(g, 2), len([x for x in ratios[kind] if x]), wins[kind][0], wins[kind][1],
               fmt(geomean(means[kind]), 2)))
    c = geomean(costs)
    if c is not None:
        add("- Cost: the QEF's extraction takes %s× the mass point's (geometric mean over every case; GL timestamps," % fmt(c, 2))
        add("  so on a software rasteriser also the CPU's load at the time).")
    add("- Default (`field.placement`, `geometry::kDefaultPlacement`): `%s`." % r["default_placement"])
    add("")
    add("Rerun: `tallow probe placement --shapes %s --res %s --repeats %d --out placement.json`."
        % (",".join(s["shape"] for s in r["shapes"]),
           ",".join(str(row["res"]) for row in r["shapes"][0]["rows"]), r["repeats"]))
    add("")
    return lines


def main(argv):
    splice = len(argv) == 3 and argv[0] == "splice"
    if splice:
        argv = argv[1:]
    if len(argv) != 2:
        sys.exit(__doc__)
    with open(argv[0]) as f:
        r = json.load(f)
    lines = section(r)
    if splice:
        results_sections.splice(argv[1], lines[0], lines)
    else:
        results_sections.append(argv[1], lines)


if __name__ == "__main__":
    main(sys.argv[1:])
