#!/usr/bin/env python3
"""Independent double-precision reference for three BSSRDF models (one colour band).

Written from the papers only (no look at the C++/GLSL implementation):
  [DD]  Frisvad, Hachisuka, Kjeldsen 2014, "Directional dipole model for subsurface
        scattering", ACM TOG 34(1) -- ../shared/papers/directional-dipole.txt
  [RM]  Dal Corso, Frisvad, Mosegaard, Baerentzen, "Interactive directional subsurface
        scattering and transport of emergent light" -- its appendix A transcribes [DD];
        its Sec. 4 / Fig. 14 uses photon beam diffusion with the clamp
        d_r >= 0.25/(sigma_a + sigma_t).
  [JM]  Jensen, Marschner, Levoy, Hanrahan 2001, "A practical model for subsurface light
        transport" (standard dipole).
  [PBD] Habel, Christensen, Jarosz 2013, "Photon beam diffusion: a hybrid Monte Carlo
        method for subsurface scattering", CGF 32(4) (with Grosjean's diffusion
        coefficient and the "better dipole" boundary of d'Eon 2012).
  [dEI] d'Eon, Irving 2011 (C_phi, C_E fits, quoted in [DD] appendix A).

Standard library only.  Lengths in mm, coefficients in 1/mm, S_d in 1/mm^2.

CONVENTIONS (every choice the papers leave open, numbered so reports can refer to them)
---------------------------------------------------------------------------------------
C1  eta = eta_2/eta_1 = (index of the medium)/(index outside) ([DD] below Eq. 11).
C2  w_i is the unit vector from x_i TOWARD the light; n_i, n_o are outward unit normals.
    All direction inputs are normalised here (the probe's inputs are unit to 1e-16
    anyway).
C3  "sd" is the diffusive part S_d only: no Fresnel transmittance T_12, T_21 and no
    reduced-intensity term S_deltaE ([DD] Eq. 3; [JM] S_d = R_d/pi without F_t).
C4  Refracted direction ([RM] appendix A, the vector form of the law of refraction):
        w12 = (1/eta) ((w_i.n_i) n_i - w_i) - n_i sqrt(1 - (1 - (w_i.n_i)^2)/eta^2).
    It points INTO the medium (w12.n_i < 0).  The formula is used unchanged when
    w_i.n_i <= 0 (light from behind the tangent plane): the tangential part does not
    depend on the sign of w_i.n_i and the normal part is always -n_i sqrt(..), so this is
    the refraction of w_i mirrored to the lit side.
C5  Total internal reflection (only possible for eta < 1, when 1 - (1-c^2)/eta^2 < 0):
    default 'graze': the radicand is clamped to 0 and w12 is normalised, i.e. w12 is the
    unit tangent -(w_i - (w_i.n_i) n_i)/|..|.  This is the continuous limit at the critical
    angle.  Alternative 'zero' (option tir='zero'): S_d = 0 (no light enters).
C6  C_phi(eta), C_E(eta) are the [dEI] polynomial fits of [DD] appendix A,
        C_phi = (1 - 2C_1)/4,  C_E = (1 - 3C_2)/2,
    with branch eta < 1 / eta >= 1 chosen on the ARGUMENT (so C_phi(1/eta) uses the
    branch of 1/eta).  Numerically (see c1_c2_numeric) the fits reproduce
        2C_1(eta) = 2 int_0^1 R(1/eta, mu) mu dmu,   3C_2(eta) = 3 int_0^1 R(1/eta, mu) mu^2 dmu,
    where R(1/eta, mu) is the Fresnel reflectance for light INSIDE the medium hitting the
    boundary at internal cosine mu (TIR included).  This is how Eqs. 28-29 are read:
    the hemisphere of Eqs. 28-29 is the set of internal directions toward the boundary,
    T_21 = 1 - R(1/eta, mu).  (Reading it with the external reflectance R(eta, mu) gives
    2C_1(1.3) = 0.061 instead of the fit's 0.445, so that reading is rejected.)
C7  Directional dipole ([DD] Eqs. 20-26, [RM] appendix A):
      D = 1/(3 sigma_t'), sigma_t' = sigma_s (1-g) + sigma_a, alpha' = sigma_s'/sigma_t',
      sigma_tr = sqrt(sigma_a/D), sigma_t = sigma_a + sigma_s,
      d_e = 2.131 D / sqrt(alpha')                                  (Eq. 21)
      A   = (1 - C_E(eta)) / (2 C_phi(eta))                          (Eq. 22)
      x = x_o - x_i, r = |x|,
      mu_0 = -n_o . w12                       (Eq. 24 text; n_o outward, w12 inward, so
                                               mu_0 > 0 = "frontlit" at x_o)
      cos_beta = -sqrt((r^2 - (x.w12)^2) / (r^2 + d_e^2))             (Eq. 25; the
                 radicand's numerator is clamped at 0 against rounding)
      d_r^2 = r^2 + D mu_0 (D mu_0 - 2 d_e cos_beta)   if mu_0 > 0   (Eq. 24)
            = r^2 + 1/(3 sigma_t)^2                     otherwise
      n_i* = (x/|x|) x (n_i x x)/|n_i x x|   (Eq. 23);  n_i* = n_i if x = 0 (Eq. 23) and
             also if |n_i x x| <= 1e-12 |x| (x parallel to n_i: Eq. 23 is 0/0; our choice)
      x_v = x_i + 2 A d_e n_i*,  d_v = |x_o - x_v|,  w_v = w12 - 2 (w12.n_i*) n_i*   (Eq. 26)
      S_d = S'_d(x_o - x_i, w12, d_r) - S'_d(x_o - x_v, w_v, d_v)                     (Eq. 26)
    with S'_d(x, w, r) of Eq. 20 exactly as printed in [DD] (NOT the bracket placement of
    [RM] appendix A, which moves the last (x.n_o) term out of the C_E factor and flips its
    sign).  Eq. 20 was re-derived from Eqs. 9, 18, 19 (S'_d = M_d / (4 pi C_phi(1/eta))
    with Phi = 1, Eq. 16) and self_test checks it against a finite-difference gradient
    of Eq. 9.  In S'_d the third argument r replaces |x| everywhere (exp, 1/r^3, r^2/D and
    the 1/r^2 inside the C_E bracket: "the denominator [of cos theta] is corrected",
    end of Sec. 3.3.3) while x itself is uncorrected.  The same n_o (outward normal at
    x_o) is used for both sources.
    Clamped value: max(0, S_d)  ([DD] Sec. 6.1).
C8  Standard dipole ([JM] Eq. 4-5, as specified in the brief):
      D = 1/(3 sigma_t'), sigma_tr = sqrt(3 sigma_a sigma_t'), alpha' = sigma_s'/sigma_t',
      F_dr = -1.440/eta^2 + 0.710/eta + 0.668 + 0.0636 eta,  A = (1+F_dr)/(1-F_dr),
      z_r = 1/sigma_t', z_v = z_r + 4 A D, r = |x_o - x_i| (3D distance, normals unused),
      d_r = sqrt(r^2 + z_r^2), d_v = sqrt(r^2 + z_v^2),
      R_d = alpha'/(4 pi) [ z_r (1 + sigma_tr d_r) e^{-sigma_tr d_r}/d_r^3
                           + z_v (1 + sigma_tr d_v) e^{-sigma_tr d_v}/d_v^3 ],
      S_d = R_d / pi;   clamped = max(0, S_d) = S_d.
C9  Photon beam diffusion, multiple scattering only ([PBD]; single scattering and the
    Fresnel factors are excluded):
      sigma_s' = (1-g) sigma_s, sigma_t' = sigma_a + sigma_s', alpha' = sigma_s'/sigma_t',
      sigma_t = sigma_a + sigma_s,
      D_G = (2 sigma_a + sigma_s') / (3 sigma_t'^2)          (Grosjean, as in [PBD])
      sigma_tr = sqrt(sigma_a / D_G),
      C_phi = C_phi(eta), C_E = C_E(eta), A = (1 - C_E)/(2 C_phi)  (= (1+3C_2)/(1-2C_1)),
      z_b = 2 A D_G (extrapolation distance), d_e := 2 z_b = 4 A D_G,
      beam: x_r(t) = x_i + t w12, t >= 0 (w12 as C4/C5),
      d_r(t) = |x_o - x_r(t)|                         (true 3D distance),
      z_r(t) = t (-w12 . n_i)                          (depth below the tangent plane at x_i),
      d_v(t) = sqrt(d_r^2 + 2 z_r d_e + d_e^2)
               (virtual source mirrored in the extrapolated plane z = -z_b of x_i's tangent
                plane, keeping the lateral offset of the real source: exact |x_o - x_v| when
                x_o lies in that tangent plane),
      dc_r = max(d_r, 0.25/(sigma_a + sigma_t))        ([RM] Sec. 4 clamp, applied to every
                                                        d_r that is in a denominator; the
                                                        exponentials and (1+sigma_tr d_r)
                                                        use the unclamped d_r),
      E(t) = C_phi/D_G (e^{-sigma_tr d_r}/dc_r - e^{-sigma_tr d_v}/d_v)
           + C_E ( z_r (1+sigma_tr d_r) e^{-sigma_tr d_r}/dc_r^3
                 + (z_r + d_e)(1+sigma_tr d_v) e^{-sigma_tr d_v}/d_v^3 ),
      kappa(t) = 1 - exp(-2 sigma_t (d_r + t))         ([PBD] boundary correction),
      S_d = 1/(4 C_phi(1/eta)) * (1/pi) * int_0^inf sigma_s' e^{-sigma_t' t} kappa(t)
                                               * alpha'/(4 pi) * E(t) dt.
    I.e. R_pt = alpha' (C_phi phi + C_E D n.grad phi)/(4 pi) is the better-dipole
    exitance of a Grosjean point source (strength alpha'), the beam emits the first
    reduced scattering events with density sigma_s' e^{-sigma_t' t}, and R -> S uses the
    same 1/(4 C_phi(1/eta) pi) normalisation as [DD] Eq. 20.  n_o is not used.
    Clamped value: max(0, S_d).
    Variants selectable for cross-checking (Conventions): pbd_kappa = 'sigma_t_t'
    (default, above) | 'sigma_tp_zr' (1 - exp(-2 sigma_t'(d_r + z_r))) | 'none';
    pbd_clamp = 'denominators' (default) | 'flux' (only the 1/dc_r^3 term) | 'none';
    pbd_clamp_value = 'sa_plus_st' (0.25/(sigma_a+sigma_t), default, [RM] text) | 'st'
    (0.25/sigma_t);  pbd_virtual = 'planar' (default, d_v as above) | 'mirror'
    (d_v = |x_o - x_v| with x_v = x_r(t) + 2 (z_r + z_b) n_i, the 3D mirror image of the
    real source in the extrapolated plane; differs from 'planar' only when x_o is off
    x_i's tangent plane).
    The integral is evaluated by globally adaptive Gauss-Kronrod (7/15) to 1e-9 relative
    (|K15 - G7| summed over panels, no error-estimate damping), with breakpoints at t = 0,
    at the closest approach of the beam to x_o and where d_r crosses the clamp radius,
    and the tail beyond the last breakpoint mapped by t = t_e - ln(1-u)/sigma_t'.
"""

import math

PI = math.pi

# ----------------------------------------------------------------------------------
# small vector helpers (3-tuples)
# ----------------------------------------------------------------------------------


def vadd(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def vsub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def vscale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def vdot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def vcross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def vnorm(a):
    return math.sqrt(vdot(a, a))


def vnormalize(a):
    n = vnorm(a)
    if not n > 0.0:
        raise ValueError("cannot normalise a zero vector")
    return (a[0] / n, a[1] / n, a[2] / n)


# ----------------------------------------------------------------------------------
# conventions
# ----------------------------------------------------------------------------------


class Conventions:
    """Switchable conventions (defaults are the ones documented as C5 and C9)."""

    CHOICES = {
        "tir": ("graze", "zero"),
        "pbd_kappa": ("sigma_t_t", "sigma_tp_t", "sigma_tp_zr", "none"),
        "jensen_eta": ("raw", "clamp"),
        "pbd_clamp": ("denominators", "flux", "none"),
        "pbd_clamp_value": ("sa_plus_st", "st"),
        "pbd_virtual": ("planar", "mirror"),
    }

    def __init__(self, **kw):
        self.tir = "graze"
        self.pbd_kappa = "sigma_t_t"
        self.jensen_eta = "raw"
        self.pbd_clamp = "denominators"
        self.pbd_clamp_value = "sa_plus_st"
        self.pbd_virtual = "planar"
        for k, v in kw.items():
            self.set(k, v)

    def set(self, key, value):
        if key not in self.CHOICES:
            raise ValueError("unknown convention %r (known: %s)" % (key, ", ".join(sorted(self.CHOICES))))
        if value not in self.CHOICES[key]:
            raise ValueError("convention %s must be one of %s, not %r" % (key, "|".join(self.CHOICES[key]), value))
        setattr(self, key, value)

    def describe(self):
        return ", ".join("%s=%s" % (k, getattr(self, k)) for k in sorted(self.CHOICES))


DEFAULT = Conventions()

# ----------------------------------------------------------------------------------
# adaptive Gauss-Kronrod 7/15 (QUADPACK qk15 nodes and weights)
# ----------------------------------------------------------------------------------

_XGK = (0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
        0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
        0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
        0.207784955007898467600689403773245, 0.000000000000000000000000000000000)
_WGK = (0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
        0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
        0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
        0.204432940075298892414161999234649, 0.209482141084727828012999174891714)
_WG = (0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
       0.381830050505118944950369775488975, 0.417959183673469387755102040816327)


def _as_tuple(v):
    return v if isinstance(v, tuple) else (v,)


def gk15(f, a, b):
    """One Gauss-Kronrod 7/15 panel.  f returns a float or a tuple of floats; the error
    estimate |K15 - G7| is that of component 0.  Returns (values, err)."""
    c = 0.5 * (a + b)
    h = 0.5 * (b - a)
    fc = _as_tuple(f(c))
    n = len(fc)
    rk = [_WGK[7] * v for v in fc]
    rg = _WG[3] * fc[0]
    for j in range(7):
        dx = h * _XGK[j]
        f1 = _as_tuple(f(c - dx))
        f2 = _as_tuple(f(c + dx))
        for k in range(n):
            rk[k] += _WGK[j] * (f1[k] + f2[k])
        if j % 2 == 1:
            rg += _WG[(j - 1) // 2] * (f1[0] + f2[0])
    vals = tuple(h * v for v in rk)
    err = abs(vals[0] - h * rg)
    return vals, err


class IntegrationResult:
    def __init__(self, values, error, converged, panels):
        self.values = values
        self.value = values[0]
        self.error = error
        self.converged = converged
        self.panels = panels


def integrate(segments, rel_tol=1e-9, abs_tol=0.0, max_panels=20000):
    """Globally adaptive integration of a sum of pieces.

    segments: list of (f, a, b); the result is sum_i int_{a_i}^{b_i} f_i.  All f_i
    return the same number of components; component 0 drives the error control.
    Stops when sum |K15 - G7| <= max(abs_tol, rel_tol * |I_0|)."""
    import heapq
    heap = []
    counter = 0
    for f, a, b in segments:
        if b <= a:
            continue
        vals, err = gk15(f, a, b)
        heapq.heappush(heap, (-err, counter, f, a, b, vals, err))
        counter += 1
    if not heap:
        return IntegrationResult((0.0,), 0.0, True, 0)
    converged = False
    while True:
        n = len(heap[0][5])
        total = [math.fsum(item[5][k] for item in heap) for k in range(n)]
        toterr = math.fsum(item[6] for item in heap)
        if toterr <= max(abs_tol, rel_tol * abs(total[0])):
            converged = True
            break
        if len(heap) >= max_panels:
            break
        _, _, f, a, b, _, _ = heapq.heappop(heap)
        m = 0.5 * (a + b)
        if not (a < m < b):  # cannot bisect further
            converged = False
            break
        for lo, hi in ((a, m), (m, b)):
            vals, err = gk15(f, lo, hi)
            heapq.heappush(heap, (-err, counter, f, lo, hi, vals, err))
            counter += 1
    return IntegrationResult(tuple(total), toterr, converged, len(heap))


# ----------------------------------------------------------------------------------
# Fresnel
# ----------------------------------------------------------------------------------


def fresnel_reflectance(eta, cos_i):
    """Exact unpolarised Fresnel reflectance for light arriving from the side with index
    n_1 onto a side with index n_2, eta = n_2/n_1, cos_i = cosine of the angle of
    incidence (the sign is ignored).  Returns 1 under total internal reflection."""
    ci = min(abs(cos_i), 1.0)
    sin_t2 = (1.0 - ci * ci) / (eta * eta)
    if sin_t2 >= 1.0:
        return 1.0
    ct = math.sqrt(1.0 - sin_t2)
    rs = (ci - eta * ct) / (ci + eta * ct)
    rp = (eta * ci - ct) / (eta * ci + ct)
    return 0.5 * (rs * rs + rp * rp)


def fresnel_transmittance(eta, cos_i):
    """T = 1 - R (same arguments as fresnel_reflectance)."""
    return 1.0 - fresnel_reflectance(eta, cos_i)


# ----------------------------------------------------------------------------------
# C_phi, C_E (appendix A of [DD])
# ----------------------------------------------------------------------------------


def two_c1_poly(eta):
    e = eta
    if e < 1.0:
        return 0.919317 - 3.4793 * e + 6.75335 * e ** 2 - 7.80989 * e ** 3 + 4.98554 * e ** 4 - 1.36881 * e ** 5
    return -9.23372 + 22.2272 * e - 20.9292 * e ** 2 + 10.2291 * e ** 3 - 2.54396 * e ** 4 + 0.254913 * e ** 5


def three_c2_poly(eta):
    e = eta
    if e < 1.0:
        return 0.828421 - 2.62051 * e + 3.36231 * e ** 2 - 1.95284 * e ** 3 + 0.236494 * e ** 4 + 0.145787 * e ** 5
    return (-1641.1 + 135.926 / e ** 3 - 656.175 / e ** 2 + 1376.53 / e + 1213.67 * e
            - 568.556 * e ** 2 + 164.798 * e ** 3 - 27.0181 * e ** 4 + 1.91826 * e ** 5)


def c_phi(eta):
    """C_phi(eta) = (1 - 2C_1)/4 with the polynomial fit (Eq. 30)."""
    return 0.25 * (1.0 - two_c1_poly(eta))


def c_e(eta):
    """C_E(eta) = (1 - 3C_2)/2 with the polynomial fit (Eq. 31)."""
    return 0.5 * (1.0 - three_c2_poly(eta))


def a_dd(eta):
    """Reflection parameter A of [DD] Eq. 22."""
    return (1.0 - c_e(eta)) / (2.0 * c_phi(eta))


def c1_c2_numeric(eta, rel_tol=1e-13):
    """(2C_1, 3C_2) by adaptive integration of the Fresnel moments (convention C6):
    2C_1 = 2 int_0^1 R(1/eta, mu) mu dmu, 3C_2 = 3 int_0^1 R(1/eta, mu) mu^2 dmu."""
    inv = 1.0 / eta
    brk = [0.0, 1.0]
    if inv < 1.0:  # total internal reflection below mu_c
        mu_c = math.sqrt(1.0 - inv * inv)
        brk = [0.0, mu_c, 1.0]

    def f(mu):
        r = fresnel_reflectance(inv, mu)
        return (2.0 * r * mu, 3.0 * r * mu * mu)

    # integrate each moment with its own error control
    segs = [(f, brk[i], brk[i + 1]) for i in range(len(brk) - 1)]
    r1 = integrate(segs, rel_tol=rel_tol, abs_tol=1e-15)
    segs2 = [((lambda mu: (f(mu)[1],)), brk[i], brk[i + 1]) for i in range(len(brk) - 1)]
    r2 = integrate(segs2, rel_tol=rel_tol, abs_tol=1e-15)
    return r1.value, r2.value


def c_phi_numeric(eta):
    """Eq. 28 by numerical integration: (1/(4 pi)) int T_21 cos dw = (1 - 2C_1)/4."""
    return 0.25 * (1.0 - c1_c2_numeric(eta)[0])


def c_e_numeric(eta):
    """Eq. 29 by numerical integration: (3/(4 pi)) int T_21 cos^2 dw = (1 - 3C_2)/2."""
    return 0.5 * (1.0 - c1_c2_numeric(eta)[1])


# ----------------------------------------------------------------------------------
# material quantities
# ----------------------------------------------------------------------------------


def check_material(sigma_a, sigma_s, g, eta):
    for name, v in (("sigma_a", sigma_a), ("sigma_s", sigma_s), ("g", g), ("eta", eta)):
        if not math.isfinite(v):
            raise ValueError("%s is not finite: %r" % (name, v))
    if sigma_a < 0.0 or sigma_s < 0.0:
        raise ValueError("negative coefficient (sigma_a=%r, sigma_s=%r)" % (sigma_a, sigma_s))
    if not (-1.0 < g < 1.0):
        raise ValueError("g must be in (-1, 1): %r" % g)
    if not eta > 0.0:
        raise ValueError("eta must be > 0: %r" % eta)
    if sigma_s * (1.0 - g) <= 0.0:
        raise ValueError("reduced scattering coefficient must be > 0")


def f_dr_jensen(eta):
    """Diffuse Fresnel reflectance fit used by [JM]."""
    return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta


def a_jensen(eta):
    f = f_dr_jensen(eta)
    return (1.0 + f) / (1.0 - f)


# ----------------------------------------------------------------------------------
# refraction (conventions C4, C5)
# ----------------------------------------------------------------------------------


def refract_in(wi, ni, eta, conv=DEFAULT):
    """Refracted direction w12 (into the medium) for w_i toward the light.
    Returns (w12, tir) where tir is True when total internal reflection occurred; with
    conv.tir == 'zero' w12 is None in that case."""
    c = vdot(wi, ni)
    tang = vscale(vsub(vscale(ni, c), wi), 1.0 / eta)  # (1/eta)((w.n)n - w)
    k = 1.0 - (1.0 - c * c) / (eta * eta)
    if k >= 0.0:
        return vsub(tang, vscale(ni, math.sqrt(k))), False
    if conv.tir == "zero":
        return None, True
    return vnormalize(tang), True


def is_tir(wi, ni, eta):
    wi = vnormalize(wi)
    ni = vnormalize(ni)
    c = vdot(wi, ni)
    return 1.0 - (1.0 - c * c) / (eta * eta) < 0.0


# ----------------------------------------------------------------------------------
# standard dipole (C8)
# ----------------------------------------------------------------------------------


def standard_rd(r, sigma_a, sigma_s, g, eta):
    """Jensen et al. 2001 diffuse reflectance R_d(r) (1/mm^2).  Returns (R_d, magnitude)."""
    sps = sigma_s * (1.0 - g)
    spt = sigma_a + sps
    alpha = sps / spt
    d = 1.0 / (3.0 * spt)
    s_tr = math.sqrt(3.0 * sigma_a * spt)
    a = a_jensen(eta)
    zr = 1.0 / spt
    zv = zr + 4.0 * a * d
    dr = math.sqrt(r * r + zr * zr)
    dv = math.sqrt(r * r + zv * zv)
    tr = zr * (1.0 + s_tr * dr) * math.exp(-s_tr * dr) / (dr * dr * dr)
    tv = zv * (1.0 + s_tr * dv) * math.exp(-s_tr * dv) / (dv * dv * dv)
    k = alpha / (4.0 * PI)
    return k * (tr + tv), k * (abs(tr) + abs(tv))


def standard_total_rd_closed_form(sigma_a, sigma_s, g, eta):
    """(alpha'/2)(1 + exp(-(4/3) A sqrt(3(1-alpha')))) exp(-sqrt(3(1-alpha')))  [JM]."""
    sps = sigma_s * (1.0 - g)
    spt = sigma_a + sps
    alpha = sps / spt
    a = a_jensen(eta)
    s = math.sqrt(3.0 * (1.0 - alpha))
    return 0.5 * alpha * (1.0 + math.exp(-4.0 / 3.0 * a * s)) * math.exp(-s)


def standard_sd(xi, ni, wi, xo, no, sigma_a, sigma_s, g, eta, conv=DEFAULT):
    """S_d = R_d(|x_o - x_i|)/pi.  Returns (sd, sd_clamped, magnitude)."""
    check_material(sigma_a, sigma_s, g, eta)
    r = vnorm(vsub(xo, xi))
    # jensen_eta='clamp': evaluate the F_dr fit at eta clamped to [1, 2.5], where the fit is a
    # reflectance (it goes negative below eta ~ 0.70); 'raw' uses the fit as printed.
    eta_fit = min(max(eta, 1.0), 2.5) if conv.jensen_eta == "clamp" else eta
    rd, mag = standard_rd(r, sigma_a, sigma_s, g, eta_fit)
    sd = rd / PI
    return sd, max(0.0, sd), mag / PI


# ----------------------------------------------------------------------------------
# directional dipole (C7)
# ----------------------------------------------------------------------------------


class _DDParams:
    def __init__(self, sigma_a, sigma_s, g, eta):
        self.sps = sigma_s * (1.0 - g)
        self.spt = sigma_a + self.sps
        self.alpha = self.sps / self.spt
        self.st = sigma_a + sigma_s
        self.D = 1.0 / (3.0 * self.spt)
        self.s_tr = math.sqrt(sigma_a / self.D)
        self.de = 2.131 * self.D / math.sqrt(self.alpha)  # Eq. 21
        self.cphi = c_phi(eta)
        self.ce = c_e(eta)
        self.cphi_inv = c_phi(1.0 / eta)
        self.A = (1.0 - self.ce) / (2.0 * self.cphi)  # Eq. 22


def dd_s_prime(x, w, r, no, p):
    """S'_d(x, w, r) of [DD] Eq. 20 (r may be a corrected distance; x is not corrected).
    Returns (value, magnitude) with magnitude = sum of |terms| times the prefactor."""
    s = p.s_tr * r
    xw = vdot(x, w)
    xn = vdot(x, no)
    wn = vdot(w, no)
    pref = 1.0 / (4.0 * p.cphi_inv) / (4.0 * PI * PI) * math.exp(-s) / (r * r * r)
    t1 = p.cphi * (r * r / p.D)
    t2 = p.cphi * 3.0 * (1.0 + s) * xw
    t3 = -p.ce * 3.0 * p.D * (1.0 + s) * wn
    t4 = p.ce * (1.0 + s) * xn
    t5 = p.ce * 3.0 * p.D * (3.0 * (1.0 + s) + s * s) / (r * r) * xw * xn
    val = pref * (t1 + t2 + t3 + t4 + t5)
    mag = abs(pref) * (abs(t1) + abs(t2) + abs(t3) + abs(t4) + abs(t5))
    return val, mag


def dd_s_prime_alt_transcription(x, w, r, no, p):
    """The bracket placement of [RM] appendix A (for the self-test only):
    [C_phi(..) - C_E (3D(1+s) w.n_o) - ((1+s) + 3D(...)/r^2 x.w) x.n_o]."""
    s = p.s_tr * r
    xw = vdot(x, w)
    xn = vdot(x, no)
    wn = vdot(w, no)
    pref = 1.0 / (4.0 * p.cphi_inv) / (4.0 * PI * PI) * math.exp(-s) / (r * r * r)
    br = (p.cphi * (r * r / p.D + 3.0 * (1.0 + s) * xw)
          - p.ce * 3.0 * p.D * (1.0 + s) * wn
          - ((1.0 + s) + 3.0 * p.D * (3.0 * (1.0 + s) + s * s) / (r * r) * xw) * xn)
    return pref * br


def modified_normal(xi, ni, xo):
    """n_i* of [DD] Eq. 23 (with the fall-backs of convention C7)."""
    x = vsub(xo, xi)
    r = vnorm(x)
    if r == 0.0:
        return ni
    c = vcross(ni, x)
    lc = vnorm(c)
    if lc <= 1e-12 * r:
        return ni
    return vcross(vscale(x, 1.0 / r), vscale(c, 1.0 / lc))


def directional_sd(xi, ni, wi, xo, no, sigma_a, sigma_s, g, eta, conv=DEFAULT, parts=False):
    """Directional dipole S_d ([DD] Eq. 26).  Returns (sd, sd_clamped, magnitude)
    (or a dict of intermediate values if parts=True)."""
    check_material(sigma_a, sigma_s, g, eta)
    ni = vnormalize(ni)
    no = vnormalize(no)
    wi = vnormalize(wi)
    p = _DDParams(sigma_a, sigma_s, g, eta)
    w12, tir = refract_in(wi, ni, eta, conv)
    if w12 is None:
        return 0.0, 0.0, 0.0
    x = vsub(xo, xi)
    r2 = vdot(x, x)
    xw = vdot(x, w12)
    mu0 = -vdot(no, w12)
    if mu0 > 0.0:  # frontlit
        cos_beta = -math.sqrt(max(0.0, r2 - xw * xw) / (r2 + p.de * p.de))
        dr2 = r2 + p.D * mu0 * (p.D * mu0 - 2.0 * p.de * cos_beta)
    else:  # backlit
        dr2 = r2 + 1.0 / (3.0 * p.st) ** 2
    dr = math.sqrt(dr2)
    nstar = modified_normal(xi, ni, xo)
    xv = vadd(xi, vscale(nstar, 2.0 * p.A * p.de))
    wv = vsub(w12, vscale(nstar, 2.0 * vdot(w12, nstar)))
    xov = vsub(xo, xv)
    dv = vnorm(xov)
    sr, mr = dd_s_prime(x, w12, dr, no, p)
    sv, mv = dd_s_prime(xov, wv, dv, no, p)
    sd = sr - sv
    if parts:
        return dict(sd=sd, sr=sr, sv=sv, w12=w12, tir=tir, mu0=mu0, dr=dr, dv=dv,
                    nstar=nstar, xv=xv, wv=wv, params=p)
    return sd, max(0.0, sd), mr + mv


# ----------------------------------------------------------------------------------
# photon beam diffusion (C9)
# ----------------------------------------------------------------------------------


def pbd_sd(xi, ni, wi, xo, no, sigma_a, sigma_s, g, eta, conv=DEFAULT, rel_tol=1e-9,
           return_result=False):
    """PBD multiple scattering S_d (convention C9).  Returns (sd, sd_clamped, magnitude)."""
    check_material(sigma_a, sigma_s, g, eta)
    ni = vnormalize(ni)
    wi = vnormalize(wi)
    w12, tir = refract_in(wi, ni, eta, conv)
    if w12 is None:
        return 0.0, 0.0, 0.0
    sps = sigma_s * (1.0 - g)
    spt = sigma_a + sps
    alpha = sps / spt
    st = sigma_a + sigma_s
    dg = (2.0 * sigma_a + sps) / (3.0 * spt * spt)
    s_tr = math.sqrt(sigma_a / dg)
    cph = c_phi(eta)
    ce = c_e(eta)
    a = (1.0 - ce) / (2.0 * cph)
    de = 4.0 * a * dg
    if conv.pbd_clamp == "none":
        cmin = 0.0
    elif conv.pbd_clamp_value == "sa_plus_st":
        cmin = 0.25 / (sigma_a + st)
    else:
        cmin = 0.25 / st
    clamp_phi = conv.pbd_clamp == "denominators"
    norm = 1.0 / (4.0 * c_phi(1.0 / eta)) / PI * alpha / (4.0 * PI)
    cos_t = -vdot(w12, ni)
    x = vsub(xo, xi)
    kappa_mode = conv.pbd_kappa
    mirror = conv.pbd_virtual == "mirror"
    zb2n = vscale(ni, de)  # 2 z_b n_i = d_e n_i (only for pbd_virtual="mirror")

    def h(t):
        """kappa(t) * alpha'/(4pi) * E(t) * normalisation; returns (value, |value| bound)."""
        xr = vsub(x, vscale(w12, t))
        dr = vnorm(xr)
        zr = t * cos_t
        if mirror:  # x_o - x_v with x_v = x_r + 2 (z_r + z_b) n_i
            dv = vnorm(vsub(vsub(xr, vscale(ni, 2.0 * zr)), zb2n))
        else:
            dv = math.sqrt(dr * dr + 2.0 * zr * de + de * de)
        drc = max(dr, cmin)
        drp = drc if clamp_phi else dr
        er = math.exp(-s_tr * dr)
        ev = math.exp(-s_tr * dv)
        p_r = cph * er / (dg * drp)
        p_v = -cph * ev / (dg * dv)
        e_r = ce * zr * (1.0 + s_tr * dr) * er / (drc * drc * drc)
        e_v = ce * (zr + de) * (1.0 + s_tr * dv) * ev / (dv * dv * dv)
        if kappa_mode == "sigma_t_t":
            kap = -math.expm1(-2.0 * st * (dr + t))
        elif kappa_mode == "sigma_tp_t":
            kap = -math.expm1(-2.0 * spt * (dr + t))
        elif kappa_mode == "sigma_tp_zr":
            kap = -math.expm1(-2.0 * spt * (dr + zr))
        else:
            kap = 1.0
        k = kap * norm
        return k * (p_r + p_v + e_r + e_v), k * (abs(p_r) + abs(p_v) + abs(e_r) + abs(e_v))

    # breakpoints
    bps = [0.0]
    tstar = vdot(x, w12)  # closest approach of the beam line to x_o
    hperp = vnorm(vsub(x, vscale(w12, tstar)))
    if tstar > 0.0:
        bps.append(tstar)
    if hperp < cmin:
        dt = math.sqrt(cmin * cmin - hperp * hperp)
        for tb in (tstar - dt, tstar + dt):
            if tb > 0.0:
                bps.append(tb)
    bps = sorted(set(bps))
    t_end = bps[-1] + max(4.0 / spt, 4.0 * hperp, 4.0 * cmin)
    bps.append(t_end)

    def f_t(t):  # finite part: sigma_s' e^{-sigma_t' t} h(t)
        q = sps * math.exp(-spt * t)
        v, m = h(t)
        return (q * v, q * m)

    tail_scale = alpha * math.exp(-spt * t_end)

    def f_u(u):  # tail: t = t_end - ln(1-u)/sigma_t', sigma_s' e^{-sigma_t' t} dt = alpha e^{-sigma_t' t_end} du
        t = t_end - math.log1p(-u) / spt
        v, m = h(t)
        return (tail_scale * v, tail_scale * m)

    segs = [(f_t, bps[i], bps[i + 1]) for i in range(len(bps) - 1)]
    segs.append((f_u, 0.0, 1.0))
    # first pass: magnitude scale for the absolute tolerance (guards against cancellation)
    res = integrate(segs, rel_tol=rel_tol, abs_tol=0.0, max_panels=4000)
    mag = res.values[1]
    if not res.converged:
        res = integrate(segs, rel_tol=rel_tol, abs_tol=1e-12 * mag, max_panels=40000)
        mag = res.values[1]
        if not res.converged:
            raise ArithmeticError("PBD reference integral did not converge (error %.3g of %.3g)"
                                  % (res.error, res.value))
    sd = res.value
    if return_result:
        return sd, max(0.0, sd), mag, res
    return sd, max(0.0, sd), mag


MODELS = {
    "standard": standard_sd,
    "directional": directional_sd,
    "pbd": pbd_sd,
}


def evaluate(model, cfg, conv=DEFAULT):
    """cfg: dict with the probe's column names.  Returns (sd, sd_clamped, magnitude)."""
    xi = (cfg["xi_x"], cfg["xi_y"], cfg["xi_z"])
    ni = (cfg["ni_x"], cfg["ni_y"], cfg["ni_z"])
    wi = (cfg["wi_x"], cfg["wi_y"], cfg["wi_z"])
    xo = (cfg["xo_x"], cfg["xo_y"], cfg["xo_z"])
    no = (cfg["no_x"], cfg["no_y"], cfg["no_z"])
    return MODELS[model](xi, ni, wi, xo, no, cfg["sigma_a"], cfg["sigma_s"], cfg["g"], cfg["eta"], conv=conv)
