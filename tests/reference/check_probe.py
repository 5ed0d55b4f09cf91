#!/usr/bin/env python3
"""Cross-check `tallow probe bssrdf` against the independent Python reference.

  python3 check_probe.py --tallow PATH --model standard|directional|pbd
                         [--count N] [--seed S] [--tolerance 1e-5]
                         [--floor-rel 1e-9] [--convention key=value ...] [--keep DIR]
  python3 check_probe.py --self-test

Comparison: N random configurations (deterministic from the seed) are written to a CSV
with the probe's input header, `tallow probe bssrdf --model M --precision double --in CFG
--out VALS` is run, and `sd`, `sd_clamped` of every row are compared with the reference:

    rel = |tallow - ref| / max(|ref|, floor),   floor = floor_rel * M

where M is the configuration's magnitude: the sum of the absolute values of all additive
terms that make up S_d (both sources and every term of Eq. 20 for the directional dipole;
the integral of the sum of |terms| for PBD; S_d itself for the standard dipole).  Two
correct double-precision evaluations can differ by about k * 2.2e-16 * M (k = a modest
number of rounding steps), whatever the size of the result after cancellation; with
floor_rel = 1e-9 that contributes at most k * 2.2e-7 to `rel`, well below the 1e-5
tolerance, while every result larger than 1e-9 of its own terms is still checked to full
relative precision.

Exit status: 0 = max rel <= tolerance; 1 = larger error (or non-finite output);
2 = tallow failed, files malformed, bad arguments.
"""

import argparse
import csv
import math
import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bssrdf_reference as B  # noqa: E402

INPUT_COLUMNS = ["xi_x", "xi_y", "xi_z", "ni_x", "ni_y", "ni_z", "wi_x", "wi_y", "wi_z",
                 "xo_x", "xo_y", "xo_z", "no_x", "no_y", "no_z", "sigma_a", "sigma_s", "g", "eta"]
OUTPUT_COLUMNS = ["sd", "sd_clamped"]


class CheckError(Exception):
    """An infrastructure failure: reported as one line, exit status 2."""


# ----------------------------------------------------------------------------------
# random configurations
# ----------------------------------------------------------------------------------


def _unit(rng):
    while True:
        v = (rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))
        n = B.vnorm(v)
        if n > 1e-6:
            return B.vscale(v, 1.0 / n)


def _perp_unit(rng, n):
    while True:
        u = _unit(rng)
        p = B.vsub(u, B.vscale(n, B.vdot(u, n)))
        if B.vnorm(p) > 1e-3:
            return B.vnormalize(p)


def draw_config(rng, kinds=("plane", "sphere", "free")):
    """One configuration (dict with INPUT_COLUMNS and a 'kind' label).

    kinds: 'plane'  x_o in the tangent plane of x_i, n_o = n_i;
           'sphere' x_i, x_o on a sphere (convex 70 %, concave 30 %) with radial normals,
                    covering backlit x_o when the arc is long;
           'free'   x_o anywhere at the drawn distance, n_o an independent random unit.
    |x_o - x_i| is log-uniform in [1e-3, 10] mm; w_i.n_i > 0 for 80 % of the draws and
    <= 0 for the rest; sigma_a log-uniform in [1e-4, 1], sigma_s log-uniform in [0.1, 50]
    (1/mm), g uniform in [-0.9, 0.9], eta uniform in [0.8, 1.6]."""
    kind = rng.choice(tuple(kinds))
    xi = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
    ni = _unit(rng)
    d = 10.0 ** rng.uniform(-3.0, 1.0)
    if kind == "plane":
        xo = B.vadd(xi, B.vscale(_perp_unit(rng, ni), d))
        no = ni
    elif kind == "sphere":
        phi = rng.uniform(0.01, 3.1)  # central angle between x_i and x_o
        rad = d / (2.0 * math.sin(0.5 * phi))
        u = _perp_unit(rng, ni)
        convex = rng.random() < 0.7
        s = 1.0 if convex else -1.0
        c = B.vsub(xi, B.vscale(ni, s * rad))
        radial = B.vadd(B.vscale(ni, math.cos(phi)), B.vscale(u, math.sin(phi)))
        xo = B.vadd(c, B.vscale(radial, s * rad))
        no = radial
    else:
        xo = B.vadd(xi, B.vscale(_unit(rng), d))
        no = _unit(rng)
    w = _unit(rng)
    c = B.vdot(w, ni)
    front = rng.random() < 0.8
    if (c > 0.0) != front:
        w = B.vsub(w, B.vscale(ni, 2.0 * c))  # mirror to the wanted side
    cfg = dict(zip(INPUT_COLUMNS, list(xi) + list(ni) + list(w) + list(xo) + list(no) + [
        10.0 ** rng.uniform(-4.0, 0.0),
        10.0 ** rng.uniform(-1.0, math.log10(50.0)),
        rng.uniform(-0.9, 0.9),
        rng.uniform(0.8, 1.6)]))
    cfg["kind"] = kind
    return cfg


# ----------------------------------------------------------------------------------
# files and the probe
# ----------------------------------------------------------------------------------


def write_configs(path, cfgs):
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(INPUT_COLUMNS)
        for c in cfgs:
            w.writerow([repr(float(c[k])) for k in INPUT_COLUMNS])


def run_probe(tallow, model, cfg_path, out_path, timeout):
    cmd = [tallow, "probe", "bssrdf", "--model", model, "--precision", "double",
           "--in", cfg_path, "--out", out_path]
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=timeout)
    except FileNotFoundError:
        raise CheckError("tallow not found or not executable: %s" % tallow)
    except PermissionError:
        raise CheckError("tallow is not executable: %s" % tallow)
    except OSError as e:
        raise CheckError("cannot run %s: %s" % (tallow, e))
    except subprocess.TimeoutExpired:
        raise CheckError("tallow probe bssrdf did not finish within %g s" % timeout)
    if p.returncode != 0:
        msg = (p.stderr or p.stdout).decode("utf-8", "replace").strip().splitlines()
        last = msg[-1] if msg else "(no output)"
        raise CheckError("tallow probe bssrdf exited with status %d: %s" % (p.returncode, last))
    if not os.path.isfile(out_path):
        raise CheckError("tallow probe bssrdf succeeded but wrote no %s" % out_path)


def read_values(path, cfgs):
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise CheckError("cannot read %s: %s" % (path, e))
    if not rows:
        raise CheckError("%s is empty (no header)" % path)
    header = [h.strip() for h in rows[0]]
    missing = [c for c in INPUT_COLUMNS + OUTPUT_COLUMNS if c not in header]
    if missing:
        raise CheckError("%s: header lacks column(s) %s (header: %s)" % (path, ",".join(missing), ",".join(header)))
    if header[:len(INPUT_COLUMNS)] != INPUT_COLUMNS:
        raise CheckError("%s: input columns are not first and in the contract's order" % path)
    body = [r for r in rows[1:] if any(x.strip() for x in r)]
    if len(body) != len(cfgs):
        raise CheckError("%s has %d data rows, expected %d" % (path, len(body), len(cfgs)))
    idx = {h: i for i, h in enumerate(header)}
    out = []
    for n, (r, c) in enumerate(zip(body, cfgs)):
        if len(r) != len(header):
            raise CheckError("%s row %d has %d fields, header has %d" % (path, n + 1, len(r), len(header)))
        vals = {}
        for k in INPUT_COLUMNS + OUTPUT_COLUMNS:
            s = r[idx[k]].strip()
            try:
                vals[k] = float(s)
            except ValueError:
                raise CheckError("%s row %d column %s is not a number: %r" % (path, n + 1, k, s))
        for k in INPUT_COLUMNS:
            a, b = vals[k], float(c[k])
            if not (a == b or abs(a - b) <= 1e-12 * max(abs(a), abs(b))):
                raise CheckError("%s row %d echoes %s = %r but %r was written (rows reordered or "
                                 "inputs printed without full precision?)" % (path, n + 1, k, a, b))
        out.append(vals)
    return out


# ----------------------------------------------------------------------------------
# comparison
# ----------------------------------------------------------------------------------


def compare(model, cfgs, vals, conv, tolerance, floor_rel):
    recs = []
    for n, (c, v) in enumerate(zip(cfgs, vals)):
        sd, sdc, mag = B.evaluate(model, c, conv)
        floor = floor_rel * mag if mag > 0 else 1e-300
        tir = B.is_tir((c["wi_x"], c["wi_y"], c["wi_z"]), (c["ni_x"], c["ni_y"], c["ni_z"]), c["eta"])
        for col, ref in (("sd", sd), ("sd_clamped", sdc)):
            got = v[col]
            if not math.isfinite(got):
                rel = math.inf
            else:
                rel = abs(got - ref) / max(abs(ref), floor)
            recs.append(dict(row=n, col=col, ref=ref, got=got, rel=rel, mag=mag, tir=tir, kind=c["kind"]))
    return recs


def report(model, cfgs, recs, tolerance, conv):
    rels = [r["rel"] for r in recs]
    worst = max(recs, key=lambda r: r["rel"])
    nonfinite = sum(1 for r in recs if not math.isfinite(r["got"]))
    print("model %s, %d configurations, reference conventions: %s" % (model, len(cfgs), conv.describe()))
    for col in OUTPUT_COLUMNS:
        rc = [r["rel"] for r in recs if r["col"] == col]
        print("  %-10s max rel %.3e   median rel %.3e" % (col, max(rc), statistics.median(rc)))
    ntir = sum(1 for c in cfgs if B.is_tir((c["wi_x"], c["wi_y"], c["wi_z"]), (c["ni_x"], c["ni_y"], c["ni_z"]), c["eta"]))
    if ntir:
        other = [r["rel"] for r in recs if not r["tir"]]
        tirr = [r["rel"] for r in recs if r["tir"]]
        print("  rows with total internal reflection at x_i (convention C5, tir=%s): %d; "
              "max rel there %.3e, elsewhere %.3e" % (conv.tir, ntir, max(tirr), max(other) if other else 0.0))
    for kind in ("plane", "sphere", "free"):
        kr = [r["rel"] for r in recs if r["kind"] == kind]
        if kr:
            print("  kind %-6s max rel %.3e (%d rows)" % (kind, max(kr), len(kr) // 2))
    nneg = sum(1 for r in recs if r["col"] == "sd" and r["ref"] < 0)
    print("  negative raw reference values: %d of %d" % (nneg, len(cfgs)))
    if nonfinite:
        print("  NON-FINITE tallow values: %d" % nonfinite)
    c = cfgs[worst["row"]]
    print("  worst: data row %d, column %s: tallow %r, reference %r, rel %.3e, magnitude %.3e, kind %s%s"
          % (worst["row"] + 1, worst["col"], worst["got"], worst["ref"], worst["rel"],
             worst["mag"], worst["kind"], ", TIR" if worst["tir"] else ""))
    print("    " + ",".join("%s=%r" % (k, c[k]) for k in INPUT_COLUMNS))
    ok = max(rels) <= tolerance and nonfinite == 0
    print("%s: max rel %.3e %s tolerance %.1e" % ("PASS" if ok else "FAIL", max(rels), "<=" if ok else ">", tolerance))
    return ok


def run_check(args, conv):
    rng = random.Random(args.seed)
    cfgs = [draw_config(rng, args.kinds.split(",")) for _ in range(args.count)]
    tmp = tempfile.mkdtemp(prefix="bssrdf_check_")
    ok = False
    try:
        cfg_path = os.path.join(tmp, "configs.csv")
        out_path = os.path.join(tmp, "values.csv")
        write_configs(cfg_path, cfgs)
        run_probe(args.tallow, args.model, cfg_path, out_path, args.timeout)
        vals = read_values(out_path, cfgs)
        recs = compare(args.model, cfgs, vals, conv, args.tolerance, args.floor_rel)
        if args.keep:
            os.makedirs(args.keep, exist_ok=True)
            shutil.copy(cfg_path, os.path.join(args.keep, "configs.csv"))
            shutil.copy(out_path, os.path.join(args.keep, "values.csv"))
            with open(os.path.join(args.keep, "reference.csv"), "w", newline="") as f:
                w = csv.writer(f, lineterminator="\n")
                w.writerow(["row", "kind", "tir", "column", "reference", "tallow", "magnitude", "rel"])
                for r in recs:
                    w.writerow([r["row"] + 1, r["kind"], int(r["tir"]), r["col"], repr(r["ref"]), repr(r["got"]),
                                repr(r["mag"]), repr(r["rel"])])
        status = 0 if report(args.model, cfgs, recs, args.tolerance, conv) else 1
        ok = True
        return status
    finally:
        if ok:
            shutil.rmtree(tmp, ignore_errors=True)  # kept for inspection after an error


# ----------------------------------------------------------------------------------
# self-test of the reference
# ----------------------------------------------------------------------------------


class _Tally:
    def __init__(self):
        self.failed = []

    def check(self, name, ok, detail):
        print("  [%s] %s: %s" % ("ok" if ok else "FAIL", name, detail))
        if not ok:
            self.failed.append(name)


def _integrate_0_inf(f, scale, decay, rel_tol=1e-11):
    """int_0^inf f(r) dr with breakpoints at multiples of `scale` and an exponential map
    r = r_e - ln(1-u)/decay on the tail."""
    bps = [0.0] + [scale * k for k in (0.1, 1.0, 3.0, 10.0)]
    r_e = bps[-1]

    def tail(u):
        r = r_e - math.log1p(-u) / decay
        return f(r) / (decay * (1.0 - u))

    segs = [(f, bps[i], bps[i + 1]) for i in range(len(bps) - 1)] + [(tail, 0.0, 1.0 - 1e-16)]
    return B.integrate(segs, rel_tol=rel_tol, abs_tol=0.0)


def _mirror_point(p, origin, m):
    return B.vsub(p, B.vscale(m, 2.0 * B.vdot(B.vsub(p, origin), m)))


def _mirror_dir(v, m):
    return B.vsub(v, B.vscale(m, 2.0 * B.vdot(v, m)))


def _rotate(v, axis, ang):
    # Rodrigues
    c, s = math.cos(ang), math.sin(ang)
    return B.vadd(B.vadd(B.vscale(v, c), B.vscale(B.vcross(axis, v), s)),
                  B.vscale(axis, B.vdot(axis, v) * (1.0 - c)))


def self_test():
    t = _Tally()
    rng = random.Random(12345)

    print("1. Gauss-Kronrod 7/15 panel exactness on [-1, 1]")
    worst_k = worst_g = 0.0
    for k in range(0, 30):
        exact = 0.0 if k % 2 else 2.0 / (k + 1)
        (vk,), _ = B.gk15(lambda x: x ** k, -1.0, 1.0)
        # G7 alone: K15 minus the reported error is not available directly; recompute
        g = sum(w * ((-x) ** k + x ** k) for w, x in zip(B._WG[:3], (B._XGK[1], B._XGK[3], B._XGK[5]))) + \
            B._WG[3] * (0.0 ** k if k else 1.0)
        if k <= 22:
            worst_k = max(worst_k, abs(vk - exact))
        if k <= 13:
            worst_g = max(worst_g, abs(g - exact))
    t.check("K15 exact to degree 22", worst_k < 1e-14, "max error %.1e" % worst_k)
    t.check("G7 exact to degree 13", worst_g < 1e-14, "max error %.1e" % worst_g)

    print("2. Fresnel")
    worst = 0.0
    for eta in (0.5, 0.8, 1.0, 1.33, 1.6, 2.0):
        worst = max(worst, abs(B.fresnel_reflectance(eta, 1.0) - ((eta - 1) / (eta + 1)) ** 2))
    t.check("normal incidence R = ((eta-1)/(eta+1))^2", worst < 1e-15, "max |diff| %.1e" % worst)
    worst = 0.0
    for _ in range(200):
        eta = rng.uniform(0.5, 2.0)
        ci = rng.uniform(0.0, 1.0)
        st2 = (1 - ci * ci) / eta ** 2
        if st2 >= 1:
            continue
        ct = math.sqrt(1 - st2)
        worst = max(worst, abs(B.fresnel_transmittance(eta, ci) - B.fresnel_transmittance(1 / eta, ct)))
    t.check("reciprocity T_12(theta_i) = T_21(theta_t)", worst < 1e-12, "max |diff| %.1e" % worst)
    t.check("TIR gives T = 0", B.fresnel_transmittance(1 / 1.5, 0.1) == 0.0, "T(1/1.5, cos 0.1) = %g" % B.fresnel_transmittance(1 / 1.5, 0.1))

    print("3. C_phi, C_E: appendix-A polynomials vs numerical integration of Eqs. 28-29 (eta in [0.5, 2])")
    dphi = de = da = 0.0
    at = None
    for i in range(31):
        eta = 0.5 + 0.05 * i
        n1, n2 = B.c1_c2_numeric(eta)
        cpn, cen = 0.25 * (1 - n1), 0.5 * (1 - n2)
        an = (1 - cen) / (2 * cpn)
        e1, e2, e3 = abs(B.c_phi(eta) - cpn), abs(B.c_e(eta) - cen), abs(B.a_dd(eta) - an) / an
        if e2 > de:
            at = eta
        dphi, de, da = max(dphi, e1), max(de, e2), max(da, e3)
    cp1, ce1 = B.c_phi_numeric(1.0), B.c_e_numeric(1.0)
    t.check("numerical C_phi(1) = 1/4, C_E(1) = 1/2", abs(cp1 - 0.25) < 1e-14 and abs(ce1 - 0.5) < 1e-14,
            "%.16f, %.16f" % (cp1, ce1))
    print("      polynomial fit error: max |dC_phi| = %.2e, max |dC_E| = %.2e (at eta = %.2f), "
          "max rel dA = %.2e" % (dphi, de, at, da))
    t.check("fits agree within the fits' accuracy (|dC_phi| < 3e-3, |dC_E| < 1e-2)",
            dphi < 3e-3 and de < 1e-2, "see the line above")
    for eta in (1.0, 1.3, 1.5):
        n1, n2 = B.c1_c2_numeric(eta)
        print("      eta %.1f: 2C_1 fit %.6f numeric %.6f | 3C_2 fit %.6f numeric %.6f"
              % (eta, B.two_c1_poly(eta), n1, B.three_c2_poly(eta), n2))

    print("4. standard dipole: int R_d(r) 2 pi r dr vs Jensen's closed form")
    worst = 0.0
    for sa, ss, g, eta in ((0.0041, 2.62, 0.0, 1.3), (0.01, 1.0, 0.0, 1.0), (1.0, 0.1, 0.9, 1.6),
                           (1e-4, 50.0, -0.9, 0.8), (0.5, 5.0, 0.5, 1.33), (0.002, 0.3, 0.2, 1.1)):
        spt = sa + ss * (1 - g)
        s_tr = math.sqrt(3 * sa * spt)
        res = _integrate_0_inf(lambda r: B.standard_rd(r, sa, ss, g, eta)[0] * 2 * math.pi * r,
                               1.0 / spt, s_tr)
        cf = B.standard_total_rd_closed_form(sa, ss, g, eta)
        rel = abs(res.value - cf) / cf
        worst = max(worst, rel)
        print("      sa=%g ss=%g g=%g eta=%g: numeric %.15f closed %.15f rel %.1e" % (sa, ss, g, eta, res.value, cf, rel))
    t.check("total diffuse reflectance", worst < 1e-9, "max rel %.1e" % worst)

    print("5. directional dipole: Eq. 20 vs M_d = C_phi phi - C_E D n_o.grad(phi) from Eqs. 9, 18 (Eq. 16)")
    worst = 0.0
    worst_alt = 0.0
    for _ in range(200):
        sa = 10 ** rng.uniform(-4, 0)
        ss = 10 ** rng.uniform(-1, math.log10(50))
        g = rng.uniform(-0.9, 0.9)
        eta = rng.uniform(0.8, 1.6)
        p = B._DDParams(sa, ss, g, eta)
        w = _unit(rng)
        no = _unit(rng)
        x = B.vscale(_unit(rng), 10 ** rng.uniform(-2, 0.5))

        def phi(y):  # Eq. 9 with Phi = 1
            r = B.vnorm(y)
            cos_t = B.vdot(y, w) / r
            return (1 / (4 * math.pi * p.D) * math.exp(-p.s_tr * r) / r
                    * (1 + 3 * p.D * (1 + p.s_tr * r) / r * cos_t))

        def dphi_dn(y):  # directional derivative along n_o, Richardson-extrapolated central differences
            hh = 1e-3 * B.vnorm(y)

            def cd(h):
                return (phi(B.vadd(y, B.vscale(no, h))) - phi(B.vsub(y, B.vscale(no, h)))) / (2 * h)
            return (4 * cd(hh / 2) - cd(hh)) / 3

        r = B.vnorm(x)
        md = p.cphi * phi(x) - p.ce * p.D * dphi_dn(x)
        expect = md / (4 * math.pi * p.cphi_inv)
        val, mag = B.dd_s_prime(x, w, r, no, p)
        worst = max(worst, abs(val - expect) / mag)
        worst_alt = max(worst_alt, abs(B.dd_s_prime_alt_transcription(x, w, r, no, p) - expect) / mag)
    t.check("Eq. 20 as printed in the TOG paper matches the derivation", worst < 1e-7,
            "max |diff|/magnitude %.1e" % worst)
    print("      (the radiosity-map appendix's bracket placement would differ by up to %.2e of the magnitude)" % worst_alt)

    print("6. symmetry")
    worst = {"standard": 0.0, "directional": 0.0, "pbd": 0.0}
    for n in range(240):
        c = draw_config(rng)
        model = ("directional", "directional", "standard", "pbd")[n % 4]
        xi = (c["xi_x"], c["xi_y"], c["xi_z"])
        ni = B.vnormalize((c["ni_x"], c["ni_y"], c["ni_z"]))
        wi = B.vnormalize((c["wi_x"], c["wi_y"], c["wi_z"]))
        xo = (c["xo_x"], c["xo_y"], c["xo_z"])
        no = (c["no_x"], c["no_y"], c["no_z"])
        m = B.vnormalize(B.vcross(ni, wi))  # normal of the plane of incidence (through x_i)
        args = (c["sigma_a"], c["sigma_s"], c["g"], c["eta"])
        a = B.MODELS[model](xi, ni, wi, xo, no, *args)
        b = B.MODELS[model](xi, ni, wi, _mirror_point(xo, xi, m), _mirror_dir(no, m), *args)
        worst[model] = max(worst[model], abs(a[0] - b[0]) / a[2])
    for model, v in sorted(worst.items()):
        t.check("%s: symmetric about the plane of incidence" % model, v < 1e-10,
                "max |diff|/magnitude %.1e" % v)
    worst = 0.0
    for _ in range(100):
        c = draw_config(rng)
        xi = (c["xi_x"], c["xi_y"], c["xi_z"])
        ni = B.vnormalize((c["ni_x"], c["ni_y"], c["ni_z"]))
        xo = B.vadd(xi, B.vscale(_perp_unit(rng, ni), 10 ** rng.uniform(-3, 1)))
        args = (c["sigma_a"], c["sigma_s"], c["g"], c["eta"])
        a = B.directional_sd(xi, ni, ni, xo, ni, *args)
        xo2 = B.vadd(xi, _rotate(B.vsub(xo, xi), ni, rng.uniform(0, 2 * math.pi)))
        b = B.directional_sd(xi, ni, ni, xo2, ni, *args)
        worst = max(worst, abs(a[0] - b[0]) / a[2])
    t.check("directional: radially symmetric at normal incidence on a plane", worst < 1e-10,
            "max |diff|/magnitude %.1e" % worst)

    print("7. directional dipole: modified tangent plane (Eq. 23)")
    worst_plane = worst_off = 0.0
    for _ in range(200):
        xi = _unit(rng)
        ni = _unit(rng)
        u = _perp_unit(rng, ni)
        xo = B.vadd(xi, B.vscale(u, 10 ** rng.uniform(-3, 1)))
        worst_plane = max(worst_plane, B.vnorm(B.vsub(B.modified_normal(xi, ni, xo), ni)))
        xo2 = B.vadd(xi, B.vscale(_unit(rng), 10 ** rng.uniform(-3, 1)))
        ns = B.modified_normal(xi, ni, xo2)
        x = B.vnormalize(B.vsub(xo2, xi))
        # unit, perpendicular to x, in span(n_i, x), on n_i's side
        e = max(abs(B.vnorm(ns) - 1), abs(B.vdot(ns, x)), abs(B.vdot(ns, B.vnormalize(B.vcross(ni, x)))))
        if B.vdot(ns, ni) < 0:
            e = 1.0
        worst_off = max(worst_off, e)
    t.check("x_o in the tangent plane: n_i* = n_i", worst_plane < 1e-12, "max |n_i* - n_i| %.1e" % worst_plane)
    t.check("x_o off the plane: n_i* unit, _|_ (x_o - x_i), in span(n_i, x_o - x_i), n_i*.n_i >= 0",
            worst_off < 1e-14, "max deviation %.1e" % worst_off)

    print("8. photon beam diffusion")
    worst = 0.0
    panels = []
    for _ in range(30):
        c = draw_config(rng)
        a = B.evaluate("pbd", c)
        xi = (c["xi_x"], c["xi_y"], c["xi_z"])
        args = [(c[k + "_x"], c[k + "_y"], c[k + "_z"]) for k in ("xi", "ni", "wi", "xo", "no")]
        r = B.pbd_sd(*args, c["sigma_a"], c["sigma_s"], c["g"], c["eta"], rel_tol=1e-13, return_result=True)
        panels.append(r[3].panels)
        worst = max(worst, abs(a[0] - r[0]) / max(abs(r[0]), 1e-12 * r[2]))
    t.check("adaptive integral at 1e-9 vs 1e-13 tolerance", worst < 1e-8,
            "max rel %.1e (up to %d panels at 1e-13)" % (worst, max(panels)))
    worst = 0.0
    mconv = B.Conventions(pbd_virtual="mirror")
    for _ in range(30):
        c = draw_config(rng)
        xi = (c["xi_x"], c["xi_y"], c["xi_z"])
        ni = B.vnormalize((c["ni_x"], c["ni_y"], c["ni_z"]))
        wi = (c["wi_x"], c["wi_y"], c["wi_z"])
        xo = B.vadd(xi, B.vscale(_perp_unit(rng, ni), 10 ** rng.uniform(-3, 1)))
        args = (c["sigma_a"], c["sigma_s"], c["g"], c["eta"])
        a = B.pbd_sd(xi, ni, wi, xo, ni, *args)
        b = B.pbd_sd(xi, ni, wi, xo, ni, *args, conv=mconv)
        worst = max(worst, abs(a[0] - b[0]) / a[2])
    t.check("x_o in x_i's tangent plane: planar d_v formula = 3D mirror image", worst < 1e-9,
            "max |diff|/magnitude %.1e" % worst)
    conv = B.Conventions(pbd_kappa="none", pbd_clamp="none")
    worst = 0.0
    for sa, ss, g, eta in ((0.05, 2.0, 0.0, 1.3), (0.3, 1.0, 0.5, 1.0), (0.01, 10.0, -0.3, 0.9)):
        sps = ss * (1 - g)
        spt = sa + sps
        alpha = sps / spt
        dg = (2 * sa + sps) / (3 * spt * spt)
        s_tr = math.sqrt(sa / dg)
        cp, ce = B.c_phi(eta), B.c_e(eta)
        dee = 4 * (1 - ce) / (2 * cp) * dg
        norm = alpha / (4 * math.pi) / (4 * B.c_phi(1 / eta) * math.pi)
        closed = norm * 2 * math.pi * sps / (spt + s_tr) * (
            cp / (dg * s_tr) * (1 - math.exp(-s_tr * dee)) + ce * (1 + math.exp(-s_tr * dee)))

        def ring(rho):
            return B.pbd_sd((0, 0, 0), (0, 0, 1), (0, 0, 1), (rho, 0, 0), (0, 0, 1), sa, ss, g, eta,
                            conv=conv, rel_tol=1e-11)[0] * 2 * math.pi * rho
        res = _integrate_0_inf(ring, 1.0 / spt, s_tr, rel_tol=1e-9)
        rel = abs(res.value - closed) / closed
        worst = max(worst, rel)
        print("      sa=%g ss=%g g=%g eta=%g: int S_d dA numeric %.12f closed %.12f rel %.1e"
              % (sa, ss, g, eta, res.value, closed, rel))
    t.check("normal incidence, no kappa, no clamp: int S_d dA = closed form", worst < 1e-7,
            "max rel %.1e" % worst)

    print("self-test: %s" % ("PASS" if not t.failed else "FAIL (%s)" % "; ".join(t.failed)))
    return 0 if not t.failed else 1


# ----------------------------------------------------------------------------------


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tallow", help="path to the tallow executable")
    ap.add_argument("--model", choices=sorted(B.MODELS))
    ap.add_argument("--count", type=int, default=1000)
    ap.add_argument("--kinds", default="plane,sphere,free",
                    help="comma list of configuration kinds to draw: plane, sphere, free")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--tolerance", type=float, default=1e-5)
    ap.add_argument("--floor-rel", type=float, default=1e-9,
                    help="relative-error floor as a fraction of the configuration's magnitude (default 1e-9)")
    ap.add_argument("--convention", action="append", default=[], metavar="KEY=VALUE",
                    help="reference convention (see bssrdf_reference.py): " + "; ".join(
                        "%s=%s" % (k, "|".join(v)) for k, v in sorted(B.Conventions.CHOICES.items())))
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds allowed for the probe")
    ap.add_argument("--keep", metavar="DIR", help="copy configs.csv, values.csv and reference.csv here")
    ap.add_argument("--self-test", action="store_true", help="check the reference against closed forms")
    args = ap.parse_args(argv)
    if args.self_test:
        return self_test()
    try:
        if not args.tallow or not args.model:
            raise CheckError("--tallow and --model are required (or use --self-test)")
        if args.count < 1:
            raise CheckError("--count must be >= 1")
        conv = B.Conventions()
        for kv in args.convention:
            if "=" not in kv:
                raise CheckError("--convention expects KEY=VALUE, got %r" % kv)
            k, v = kv.split("=", 1)
            try:
                conv.set(k.strip(), v.strip())
            except ValueError as e:
                raise CheckError(str(e))
        return run_check(args, conv)
    except CheckError as e:
        print("check_probe: error: %s" % e, file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
