#!/usr/bin/env python3
"""Independent quasi-static reference for the first slip onset of cases/cycle_slow_loading.toml.

What it solves
--------------
The paper's plane-strain block (10 m x 1 m, 10 x 1 bilinear Q4 elements, E = 1 kPa, nu = 0), top
edge fixed, bottom edge on a frictional contact with a rigid base that moves along +x at
v = 1e-9 m/s after a smooth start over 1e4 s.  The normal traction on the contact is held constant,
linear from 350 Pa at x = 0 to 1200 Pa at x = 10.  Friction: the super/subloading-surface law with
the conventions of docs/model.md ("consistent" R* law, i.e. eq. (4) without the
1/mu_k), parameters of the case (healing xi = 1e-7 /s).

It is written from the model documents only (no port of slipfront's Rust friction code) and
shares no code with slipfront; it needs numpy and scipy.

Method
------
At a plate rate inertia is negligible until the slip rate is far above the event threshold, so the
block is taken in static equilibrium at every instant (quasi-static):

    A u = P (f - f(0)),      A = K + K_n                                     (1)

K the Q4 plane-strain stiffness (2 x 2 Gauss points) of the 22 free bottom-node dofs (top nodes
fixed), K_n the contact's normal springs alpha_n * w N_a N_b (held normal: they only tie the bottom
to the base in y), P the tangential (x) nodal load of the 20 contact points (two Gauss points per
segment, weight L/2), f the contact points' tangential tractions (the traction the base exerts on
the block, +x).  The "- f(0)" is slipfront's total form M a + K u = f^0 + f_c - f_c(0): the body
starts undeformed with the tiny initial traction f0 balanced.

Eliminating u, the relative sliding velocity at the contact points is

    vbar = G fdot - v_base(t),        G = N~ A^-1 P   (20 x 20 compliance)     (2)

and the friction law in rate form at each point g (sigma = sign f, z = 1/R*):

    R     = |f| / (mu_k f_n z)
    D     = alpha_t + r (-ln R) z mu_k f_n - kappa R (z - 1)^m mu_k f_n
    Lam   = max(0, [-alpha_t sigma vbar - xi R (1 - (mu_k/mu_s) z)^n mu_k f_n] / D)
    fdot  = -alpha_t (vbar + Lam sigma)
    zdot  = -kappa (z - 1)^m Lam + xi (1 - (mu_k/mu_s) z)^n

(2) and the Lam/fdot lines are coupled and piecewise linear in vbar (loading or unloading per
point).  After the base's ramp every point loads until the fold below, so each right-hand side
takes every point on the loading branch (Lam = N/D, unclipped: one 20 x 20 linear solve for
fdot), and a terminal event (`unloads`) stops the integration if any Lam turns negative, where
that branch would no longer hold.  The ODE in y = (f[20], z[20]) is integrated by
scipy.integrate.solve_ivp(method="Radau"), with a terminal event when a segment's plastic slip rate
(the mean of Lam over its two Gauss points, as slipfront's event catalog defines it) first exceeds
the threshold 1e-8 m/s.

What it found: the quasi-static path reaches a fold (J = I + alpha_t C G singular, its smallest
singular value falling linearly in time) at t_fold = 386 696 579.8 s, with the slip rates still
at ~1e-9 m/s one second before it; there the quasi-static rates blow up (the loading-branch
check `unloads` or Radau's step-size failure stops the integration within 0.1 s of the fold).
So the quasi-static onset is the fold.  Past it the equilibrium is unstable, and with inertia the
slip runs away at a growth rate that rises from 0 as ~sqrt(t - t_fold); the dynamic onset
(threshold crossing) therefore lags t_fold by a delay set by that slow growth, estimated at the
end of the run from the linearized dynamic system (rough: order 1e3 s).  With inertia the path is
also unstable before the fold, to a slow oscillation of the low-stress end whose growth rate does
not depend on the mass (--stability); the quasi-static equations, the limit of no mass, are stable
there.  That oscillation is what slipfront's precursors grow from, seeded by its steps' errors.

Run
---
    python3 scripts/plate_rate_reference.py                      # rtol sweep 1e-8 .. 1e-12, ~4 s
    python3 scripts/plate_rate_reference.py --rtol 1e-9 1e-10
    python3 scripts/plate_rate_reference.py --compare sf.csv     # stick-phase check, see below
    python3 scripts/plate_rate_reference.py --stability          # the creep's stability with inertia, ~3 s

--stability linearizes the equations with inertia (rhs_dyn below: the same block, lumped mass, every
point on the loading branch) about the quasi-static path at times before the fold, and prints the
eigenvalue of largest real part, beside that of the quasi-static equations alone; then, at 3e5 s
before the fold, the same with the mass scaled, with kappa or xi set to 0 in the linearization,
and the shape of the growing mode.

--compare takes a table written by `slipfront export run.mcap -o sf.csv` of a slipfront run of the
same case (e.g. `slipfront run cases/cycle_slow_loading.toml --no-rrd --out-dir D --set
time.t_end=2e8 --mcap D/run.mcap`) and prints, at the recorded rows nearest 1e7, 1e8 and 2e8 s,
the segment means of f_t and 1/R* of both.  Details taken from slipfront's source (not stated in
the docs): the ramp v(t) = v s^3 (10 - 15 s + 6 s^2), s = t/T (src/dynamics/motion.rs); two Gauss
points per segment at +-1/sqrt(3), weight L/2, normal springs alpha_n w N_a N_b in K
(src/fem/assembly.rs, src/fem/curve.rs); the total form with f_c(0) subtracted (src/dynamics/system.rs).
"""

import argparse
import csv
import math
import time

import numpy as np
from scipy.integrate import solve_ivp

# ---------------------------------------------------------------- case (cases/cycle_slow_loading.toml)
MU_S, MU_K = 0.4, 0.2
ALPHA_N, ALPHA_T = 1.0e6, 1.0e6
R_EVOL, KAPPA, M_EXP = 100.0, 10.0, 1.0
XI, N_EXP = 1.0e-7, 1.0
Z0, F0 = 2.0, 1.0e-7
WIDTH, HEIGHT, NX = 10.0, 1.0, 10
E_MOD, NU = 1.0e3, 0.0
V_BASE, T_RAMP = 1.0e-9, 1.0e4
FN_LEFT, FN_RIGHT = 350.0, 1200.0
THRESHOLD = 1.0e-8
NPT = 2 * NX  # contact (Gauss) points

GAUSS = np.array([-1.0, 1.0]) / math.sqrt(3.0)


def base_velocity(t):
    """Base speed along +x: C2 ramp from rest over T_RAMP."""
    if t >= T_RAMP:
        return V_BASE
    s = max(t, 0.0) / T_RAMP
    return V_BASE * s ** 3 * (10.0 - 15.0 * s + 6.0 * s * s)


def base_displacement(t):
    if t >= T_RAMP:
        return V_BASE * (t - 0.5 * T_RAMP)
    s = max(t, 0.0) / T_RAMP
    return V_BASE * T_RAMP * s ** 4 * (2.5 - 3.0 * s + s * s)


# ---------------------------------------------------------------- body
def q4_stiffness(xy):
    """Plane-strain Q4 stiffness (8 x 8, dofs ux1,uy1,...), 2 x 2 Gauss, unit thickness."""
    c = E_MOD / ((1 + NU) * (1 - 2 * NU))
    dmat = c * np.array([[1 - NU, NU, 0], [NU, 1 - NU, 0], [0, 0, (1 - 2 * NU) / 2]])
    ke = np.zeros((8, 8))
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    for xi in GAUSS:
        for eta in GAUSS:
            dn = np.array([[0.25 * a * (1 + b * eta) for a, b in corners],
                           [0.25 * b * (1 + a * xi) for a, b in corners]])  # d/dxi, d/deta
            jac = dn @ xy
            dxy = np.linalg.solve(jac, dn)
            bmat = np.zeros((3, 8))
            bmat[0, 0::2] = dxy[0]
            bmat[1, 1::2] = dxy[1]
            bmat[2, 0::2] = dxy[1]
            bmat[2, 1::2] = dxy[0]
            ke += bmat.T @ dmat @ bmat * np.linalg.det(jac)
    return ke


def build():
    """A = K + K_n on the free dofs (bottom nodes: ux 0..10, uy 11..21), P, N~, f_n, G."""
    nb = NX + 1
    dx = WIDTH / NX
    nfree = 2 * nb
    amat = np.zeros((nfree, nfree))

    def dof(i, j, comp):  # node (i along x, j = 0 bottom / 1 top), component; None if fixed
        if j == 1:
            return None
        return i if comp == 0 else nb + i

    for e in range(NX):
        nodes = [(e, 0), (e + 1, 0), (e + 1, 1), (e, 1)]  # counter-clockwise
        xy = np.array([[i * dx, j * HEIGHT] for i, j in nodes])
        ke = q4_stiffness(xy)
        dofs = [dof(i, j, c) for i, j in nodes for c in (0, 1)]
        for a, da in enumerate(dofs):
            for b, db in enumerate(dofs):
                if da is not None and db is not None:
                    amat[da, db] += ke[a, b]
    pmat = np.zeros((nfree, NPT))   # tangential nodal load of each point's traction
    ntil = np.zeros((NPT, nfree))   # tangential displacement at each point
    fn = np.zeros(NPT)
    for e in range(NX):
        for k, g in enumerate(GAUSS):
            p = 2 * e + k
            na, nbv = 0.5 * (1 - g), 0.5 * (1 + g)
            w = 0.5 * dx
            x = e * dx + dx * 0.5 * (1 + g)
            fn[p] = FN_LEFT + (FN_RIGHT - FN_LEFT) * x / WIDTH
            ntil[p, e], ntil[p, e + 1] = na, nbv
            pmat[e, p] += w * na
            pmat[e + 1, p] += w * nbv
            # normal springs on the y dofs
            ya, yb = nb + e, nb + e + 1
            for da, ca in ((ya, na), (yb, nbv)):
                for db, cb in ((ya, na), (yb, nbv)):
                    amat[da, db] += ALPHA_N * w * ca * cb
    gmat = ntil @ np.linalg.solve(amat, pmat)
    return amat, pmat, ntil, fn, gmat


AMAT, PMAT, NTIL, FN, GMAT = build()
MUF = MU_K * FN
EYE = np.eye(NPT)


# ---------------------------------------------------------------- friction law, rates
def local_terms(f, z):
    """Per point: sign of f, the denominator D of eq. (5), its healing term H, healing and decay."""
    sig = np.sign(f)
    ratio = np.abs(f) / (MUF * z)  # R
    heal = np.maximum(1.0 - (MU_K / MU_S) * z, 0.0) ** N_EXP
    decay = np.maximum(z - 1.0, 0.0) ** M_EXP
    dden = ALPHA_T + R_EVOL * (-np.log(ratio)) * z * MUF - KAPPA * ratio * decay * MUF
    hterm = XI * ratio * heal * MUF
    return sig, dden, hterm, heal, decay


def rates_qs(t, y):
    """Quasi-static rates with every point on the loading branch of eq. (9) (Lam = N/D unclipped).

    fdot = -alpha_t C vbar + b (C = 1 - alpha_t/D, b = alpha_t sigma H/D) and vbar = G fdot - v_base
    give J fdot = alpha_t C v_base + b with J = I + alpha_t C G.  Returns fdot, zdot, Lam, J.
    The integration checks (event `unloads`) that no Lam turns negative, i.e. that this branch
    is eq. (9)'s everywhere: it is, from the end of the ramp to the onset.
    """
    f, z = y[:NPT], y[NPT:2 * NPT]
    sig, dden, hterm, heal, decay = local_terms(f, z)
    vb = base_velocity(t)
    c = 1.0 - ALPHA_T / dden
    b = ALPHA_T * sig * hterm / dden
    jmat = EYE + ALPHA_T * c[:, None] * GMAT
    fdot = np.linalg.solve(jmat, ALPHA_T * c * vb + b)
    vbar = GMAT @ fdot - vb
    lam = (-ALPHA_T * sig * vbar - hterm) / dden
    zdot = -KAPPA * decay * lam + XI * heal
    return fdot, zdot, lam, jmat


def rhs_qs(t, y):
    fdot, zdot, _, _ = rates_qs(t, y)
    return np.concatenate([fdot, zdot])


def segment_mean(lam):
    return 0.5 * (lam[0::2] + lam[1::2])


def qs_threshold(t, y):
    return segment_mean(rates_qs(t, y)[2]).max() - THRESHOLD


def qs_fold(t, y):
    """det J: the quasi-static equilibrium loses stability (and the rates blow up) where it is 0."""
    return np.linalg.det(rates_qs(t, y)[3])


def qs_unloads(t, y):
    return rates_qs(t, y)[2].min() if t > T_RAMP else 1.0


for _event in (qs_threshold, qs_fold, qs_unloads):
    _event.terminal = True
qs_threshold.direction = 1
qs_unloads.direction = -1


def y0_qs():
    return np.concatenate([np.full(NPT, F0), np.full(NPT, Z0)])


def atol_for(rtol, n_extra=()):
    """Absolute tolerances: tractions on a scale of 100 Pa, 1/R* of 1, extras as given."""
    return np.concatenate([*[np.full(NPT, scale * rtol) for scale in (1.0e2, 1.0)], *n_extra])


def quasi_static(rtol, t_stop=4.0e9):
    """Radau on the quasi-static ODE from t = 0 to the first onset (or t_stop)."""
    started = time.perf_counter()
    sol = solve_ivp(rhs_qs, (0.0, t_stop), y0_qs(), method="Radau", rtol=rtol, atol=atol_for(rtol),
                    dense_output=True, events=[qs_threshold, qs_fold, qs_unloads])
    wall = time.perf_counter() - started
    out = dict(rtol=rtol, wall=wall, nfev=sol.nfev, steps=len(sol.t) - 1, sol=sol, stop=sol.t[-1])
    for name, k in (("threshold", 0), ("fold", 1), ("unloads", 2)):
        out[name] = sol.t_events[k][0] if len(sol.t_events[k]) else float("nan")
    if sol.t[-1] < t_stop:
        # The smallest singular value of J falls linearly in time: extrapolate it to 0 from 1e4 s and
        # 1e3 s before the stop, a check on where the events stopped the integration.
        t1, t2 = sol.t[-1] - 1.0e4, sol.t[-1] - 1.0e3
        s1, s2 = (np.linalg.svd(rates_qs(t, sol.sol(t))[3], compute_uv=False)[-1] for t in (t1, t2))
        out["fold_extrapolated"] = t2 + s2 * (t2 - t1) / (s1 - s2)
        fdot, _, lam, jmat = rates_qs(t2, sol.sol(t2))
        null = np.linalg.svd(jmat)[2][-1]
        out["segment"] = int(np.argmax(np.abs(segment_mean(null))))
        out["lam_before"] = segment_mean(rates_qs(sol.t[-1] - 1.0, sol.sol(sol.t[-1] - 1.0))[2])
    return out


# ---------------------------------------------------------------- inertia: growth past the fold
RHO = 1000.0


def lumped_mass():
    """Lumped Q4 mass of the free dofs: rho * area / 4 per node and element, the same in x and y."""
    m = np.zeros(NX + 1)
    m[:-1] += RHO * (WIDTH / NX) * HEIGHT / 4.0
    m[1:] += RHO * (WIDTH / NX) * HEIGHT / 4.0
    return np.concatenate([m, m])


MASS = lumped_mass()
NDOF = 2 * (NX + 1)
FORCE0 = PMAT @ np.full(NPT, F0)


def rhs_dyn(t, y):
    """With inertia: M vdot = -A u + P (f - f(0)), udot = v, vbar = N~ v - v_base, Lam = max(0, N/D)."""
    u, v = y[:NDOF], y[NDOF:2 * NDOF]
    f, z = y[2 * NDOF:2 * NDOF + NPT], y[2 * NDOF + NPT:]
    sig, dden, hterm, heal, decay = local_terms(f, z)
    vbar = NTIL @ v - base_velocity(t)
    lam = np.maximum((-ALPHA_T * sig * vbar - hterm) / dden, 0.0)
    fdot = -ALPHA_T * (vbar + lam * sig)
    zdot = -KAPPA * decay * lam + XI * heal
    vdot = (-AMAT @ u + PMAT @ f - FORCE0) / MASS
    return np.concatenate([v, vdot, fdot, zdot])


def unstable_growth(result, taus=(1.0e4, 3.0e4)):
    """Largest real eigenvalue (1/s) of the dynamic system linearized on the quasi-static path
    continued linearly past the fold, at t_fold + tau: how fast inertia lets the slip run away."""
    sol, t0 = result["sol"], result["stop"] - 1.0
    y0 = sol.sol(t0)
    ydot = rhs_qs(t0, y0)
    rates = []
    for tau in taus:
        t = result["stop"] + tau
        state = as_dynamic(y0 + (t - t0) * ydot, ydot)
        eig = np.linalg.eigvals(jacobian(rhs_dyn, t, state, DYNAMIC_FLOORS))
        real = eig[np.abs(eig.imag) < 1e-9 * np.abs(eig).max()].real
        rates.append((tau, real.max()))
    return rates


def as_dynamic(y, ydot):
    """A quasi-static state y = (f, 1/R*) with rates ydot as a state of the equations with inertia:
    u in equilibrium with f, v its rate."""
    u = np.linalg.solve(AMAT, PMAT @ y[:NPT] - FORCE0)
    v = np.linalg.solve(AMAT, PMAT @ ydot[:NPT])
    return np.concatenate([u, v, y])


def dynamic_state(sol, t):
    """The quasi-static path's state at t as a state of the equations with inertia."""
    y = sol.sol(t)
    return as_dynamic(y, rhs_qs(t, y))


JACOBIAN_STEP = 1e-6
# Smallest scales the Jacobian's steps are taken relative to: displacements and velocities, then
# tractions and 1/R*.
DYNAMIC_FLOORS = np.concatenate([np.full(2 * NDOF, 1e-12), np.full(2 * NPT, 1e-6)])
QUASI_STATIC_FLOORS = np.full(2 * NPT, 1e-6)


def jacobian(rhs, t, state, floors):
    """Central-difference Jacobian of rhs at state, relative step JACOBIAN_STEP; floors[i] is the
    smallest scale of state[i] a step is taken relative to."""
    jac = np.zeros((state.size, state.size))
    for i in range(state.size):
        h = JACOBIAN_STEP * max(abs(state[i]), floors[i])
        up, down = state.copy(), state.copy()
        up[i] += h
        down[i] -= h
        jac[:, i] = (rhs(t, up) - rhs(t, down)) / (2.0 * h)
    return jac


def leading(jac):
    """The eigenvalue of largest real part, and its eigenvector."""
    values, vectors = np.linalg.eig(jac)
    k = int(np.argmax(values.real))
    return values[k], vectors[:, k]


def stability():
    """Prints the stability of the quasi-static path with and without inertia (see --stability)."""
    global MASS, XI, KAPPA
    r = quasi_static(1e-10)
    sol, t_fold = r["sol"], r["stop"]
    print(f"Fold at {t_fold:.1f} s (rtol 1e-10). Eigenvalue of largest real part (1/s), linearized on the path:")
    print("| before the fold (s) | with inertia: Re | Im | e-folding time (s) | quasi-static alone: Re |")
    print("|---|---|---|---|---|")
    for tau in (3e7, 1e7, 3e6, 1e6, 3e5, 1e5, 3e4, 1e4):
        t = t_fold - tau
        dyn, _ = leading(jacobian(rhs_dyn, t, dynamic_state(sol, t), DYNAMIC_FLOORS))
        qs, _ = leading(jacobian(rhs_qs, t, sol.sol(t), QUASI_STATIC_FLOORS))
        print(f"| {tau:.0e} | {dyn.real:+.3e} | {abs(dyn.imag):.3e} | {1 / dyn.real:.2e} | {qs.real:+.2e} |")
    t = t_fold - 3e5
    state = dynamic_state(sol, t)
    print(f"\nAt {3e5:.0e} s before the fold, with inertia:")
    mass = MASS.copy()
    for scale in (1e-2, 1e2):
        MASS = mass * scale
        value, _ = leading(jacobian(rhs_dyn, t, state, DYNAMIC_FLOORS))
        print(f"  mass x {scale:g}: {value.real:+.3e} {abs(value.imag):+.3e}i")
    MASS = mass
    for name in ("KAPPA", "XI"):
        kept = globals()[name]
        globals()[name] = 0.0
        value, _ = leading(jacobian(rhs_dyn, t, state, DYNAMIC_FLOORS))
        globals()[name] = kept
        print(f"  {name.lower()} = 0 in the linearization: {value.real:+.3e} {abs(value.imag):+.3e}i")
    _, mode = leading(jacobian(rhs_dyn, t, state, DYNAMIC_FLOORS))
    velocity = np.abs(mode[NDOF:NDOF + NX + 1])
    print(f"  the growing mode's x-velocity at the contact nodes x = 0, 1, ..., 10 m (largest 1): "
          f"{np.array2string(velocity / velocity.max(), precision=3)}")


def compare(path, rtol):
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    times = np.array([float(r["sim_time_s"]) for r in rows])
    picks = sorted({int(np.argmin(np.abs(times - target))) for target in (1e7, 1e8, 2e8)})
    sol = quasi_static(rtol, t_stop=times[picks[-1]] + 1.0)["sol"]
    print(f"Stick-phase check against {path} (this script at rtol {rtol:g}; segment means of the two Gauss points)")
    print("| t (s) | seg | f_t here (Pa) | f_t slipfront (Pa) | diff (Pa) | 1/R* here | 1/R* slipfront | diff |")
    print("|---|---|---|---|---|---|---|---|")
    for i in picks:
        t = times[i]
        y = sol.sol(t)
        fseg, zseg = segment_mean(y[:NPT]), segment_mean(y[NPT:])
        sf_f = np.array([float(rows[i][f"traction_t_Pa_seg{k}"]) for k in range(NX)])
        sf_z = np.array([float(rows[i][f"structure_seg{k}"]) for k in range(NX)])
        for k in (0, 4, 9):
            print(f"| {t:.6e} | {k} | {fseg[k]:.6f} | {sf_f[k]:.6f} | {fseg[k] - sf_f[k]:+.2e} | {zseg[k]:.9f} | "
                  f"{sf_z[k]:.9f} | {zseg[k] - sf_z[k]:+.2e} |")
        print(f"| | max over 0-9 | | | {np.abs(fseg - sf_f).max():.2e} | | | {np.abs(zseg - sf_z).max():.2e} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rtol", type=float, nargs="+", default=[1e-8, 1e-9, 1e-10, 1e-11, 1e-12])
    ap.add_argument("--compare", help="CSV from `slipfront export` of a run of the case (stick phase)")
    ap.add_argument("--compare-rtol", type=float, default=1e-10)
    ap.add_argument("--stability", action="store_true", help="the quasi-static path's stability with inertia")
    ap.add_argument("--jacobian-step", type=float, default=JACOBIAN_STEP,
                    help="relative step of --stability's central differences (a check on their convergence)")
    args = ap.parse_args()
    if args.stability:
        globals()["JACOBIAN_STEP"] = args.jacobian_step
        stability()
        return
    if args.compare:
        compare(args.compare, args.compare_rtol)
        return
    print("| rtol | stop = onset (s) | stopped by | fold by sigma_min extrapolation (s) | segment | "
          "steps | nfev | wall (s) |")
    print("|---|---|---|---|---|---|---|---|")
    results = []
    for rtol in args.rtol:
        r = quasi_static(rtol)
        results.append(r)
        by = [name for name in ("threshold", "fold", "unloads") if r[name] == r["stop"]]
        print(f"| {rtol:g} | {r['stop']:.4f} | {'/'.join(by)} | {r['fold_extrapolated']:.4f} | {r['segment']} | "
              f"{r['steps']} | {r['nfev']} | {r['wall']:.2f} |", flush=True)
    last = results[-1]
    y = last["sol"].sol(last["stop"] - 1.0)
    print(f"\n1 s before the stop (rtol {last['rtol']:g}): segment plastic slip rates (m/s) "
          f"{np.array2string(last['lam_before'], precision=3)}")
    print(f"segment f_t (Pa) {np.array2string(segment_mean(y[:NPT]), precision=3)}")
    print(f"segment 1/R* {np.array2string(segment_mean(y[NPT:]), precision=5)}")
    print(f"base displacement {base_displacement(last['stop']):.6f} m")
    for tau, rate in unstable_growth(last):
        print(f"inertia (rough: finite-difference Jacobian): fastest real growth rate {tau:.0e} s past the fold "
              f"{rate:.3e} /s "
              f"(a = rate/sqrt(tau) = {rate / math.sqrt(tau):.3e} s^-1.5)")


if __name__ == "__main__":
    main()
