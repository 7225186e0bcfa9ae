//! The rate form: the paper's equations as one system of ODEs, integrated by Runge–Kutta methods
//! (Tsitouras' explicit 5(4) pair, [`tsit5`]; the L-stable SDIRK 4(3), [`sdirk4`]) through one
//! adaptive driver ([`driver`]).
//!
//! Wilson's θ method ([`crate::dynamics::wilson`]) integrates the total form with an implicit friction
//! update over each step; it is second-order accurate, so a tight error costs many steps. The
//! paper's equations are also a system of ODEs in `y = (u, v, f_t, 1/R*, p)`:
//!
//! * `u̇ = v`, `M v̇ = ḟ⁰ t - K u + Σ w Ñᵀ (f_t - f_t⁰)`: eq. (14) in total form, `u` measured
//!   from the initial equilibrium as in [`crate::dynamics::wilson`];
//! * `ḟ_t` of eq. (6), switched by eq. (9), for the relative sliding velocity
//!   `v̄_t = Ñ v - v_base(t)` of eq. (13) ([`crate::friction::law::tangential_rate`]);
//! * `d(1/R*)/dt` of eq. (4) ([`crate::friction::law::structure_rate`]) and `ṗ = Λ` of eq. (5).
//!
//! Tsitouras' pair (Ch. Tsitouras, "Runge–Kutta pairs of order 5(4) satisfying only the first
//! column simplifying assumption", Comput. Math. Appl. 62 (2011) 770–775, Table 1) advances it
//! with the fifth-order solution and estimates the error from the embedded fourth-order one;
//! its last stage is the next step's first (FSAL), six right-hand sides per step. The error of
//! each component is measured against its own size plus a physical scale (below) and the
//! largest must stay within `tolerance` per step; the next step is `0.9 h (tolerance/error)^{1/5}`,
//! limited to a factor 5 up or 5 down.
//!
//! The method is explicit, and the body and its contact springs are undamped: their modes have
//! imaginary eigenvalues `±iω`. Like every explicit fifth-order pair, Tsitouras' amplifies them
//! (its stability function has `|R(iy)| ≤ 1` only up to `y = hω = 0.478`, then 1.00013 at 1,
//! 1.026 at 2, 1.28 at 3; [`tsit5::amplification`]). Its error control alone would hold `hω` of
//! the stiffest mode near 1 to 2 and let a stuck contact's ringing grow without bound, so
//! [`crate::dynamics::method`] also bounds the step by the `hω_max` at which no mode grows faster
//! than 2× in 1000 s ([`tsit5::bounded_growth`]): 17 ms on the paper's 10 × 1 mesh
//! (`ω_max ≈ 45 rad/s`). A rate, so that no step depends on when the run ends.
//!
//! The exact flow keeps every point's `R ≤ 1` and `1/R*` in `[1, μ_s/μ_k]`; the pair keeps
//! them only to its local error, so each accepted state is put back on that set where it has
//! left it, and its rate evaluated again ([`System::project`]).
//!
//! Eq. (9)'s switches between loading and unloading are kinks of the right-hand side (its
//! value continuous, its slope not), and a step across one is rejected by its error estimate.
//! Tsitouras' pair therefore holds each point on its branch of eq. (6) over a step
//! ([`System::rate_form_on_branches`], each branch smooth) and ends the step where a point's
//! switching function (the numerator `N` of eq. 5) changes sign, located along the step's
//! fourth-order dense output ([`tsit5::dense_weights`], [`driver`]), which is also the state
//! there; the point changes branch there.
//!
//! Stick/slip transitions are located, not stepped over: when a step carries a contact point's
//! plastic slip rate `Λ` across the event threshold, the step is shortened to end just past the
//! crossing (found by the Illinois variant of regula falsi on `Λ - threshold` with fifth-order
//! steps from the step's start), so that a frame lies on every onset and every end.

/// How many contact points held on their branches go through the friction law at once
/// ([`law::rates_on_branches`]): the lanes of the widest vectors of `f64` (AVX2).
const LANES: usize = 4;

/// How the right-hand side chooses each point's branch of eq. (6).
enum Switching<'a> {
    /// By eq. (9) at the point's state, at every evaluation.
    ByEq9,
    /// As given, continued past the switch; eq. (9)'s switching function into `numerator`.
    Held { branches: &'a [bool], numerator: &'a mut [f64] },
}

pub mod driver;
pub mod memory;
pub mod sdirk4;
mod trial;
pub mod tsit5;

use crate::dynamics::contact::{ContactPoint, ContactSurface, MainBody, NormalBehaviour};
use crate::dynamics::system::System;
use crate::friction::{ContactState, law};

impl System {
    /// Puts a state that a step's error has carried just outside the set the exact flow never
    /// leaves back on its edge: `1 ≤ 1/R* ≤ μ_s/μ_k`, where eq. (4)'s decay and healing vanish,
    /// and `R ≤ 1`, that is `|f_t| ≤ μ_k f_n (1/R*)`, where `Ṙ = -r ln(R) Λ` vanishes (it is
    /// negative above). The implicit update meets these exactly; the explicit pair only to its
    /// local error (`R = 1 + 2e-11` at tolerance 1e-8 under 1e-3 Pa of normal traction). Returns
    /// whether anything moved.
    pub(crate) fn project(&self, y: &mut [f64]) -> bool {
        let n = self.body.dofs();
        let m = self.contact.points.len();
        let (u, rest) = y.split_at_mut(2 * n);
        let (traction, structure) = rest[..2 * m].split_at_mut(m);
        let mut moved = false;
        for (k, ((f_t, z), &held)) in
            traction.iter_mut().zip(structure.iter_mut()).zip(&self.contact.traction_n).enumerate()
        {
            let params = self.contact.params(k);
            let f_n = if self.contact.evolves(k) { self.contact.normal_traction_at(k, &u[..n]) } else { held };
            if self.contact.evolves(k) && f_n <= 0.0 && *f_t != 0.0 {
                // Open: no traction.
                *f_t = 0.0;
                moved = true;
            }
            let inside = z.clamp(1.0, params.max_structure());
            if inside != *z {
                *z = inside;
                moved = true;
            }
            let strength = params.mu_k * f_n * *z;
            if f_n > 0.0 && f_t.abs() > strength {
                *f_t = strength.copysign(*f_t);
                moved = true;
            }
        }
        moved
    }

    /// The right-hand side `ẏ = f(t, y)` (module docs); fills `lambda` with each point's `Λ`.
    pub(crate) fn rate_form(&self, t: f64, y: &[f64], rate: &mut [f64], lambda: &mut [f64]) {
        self.rate_form_switched(t, y, rate, lambda, &mut Switching::ByEq9);
    }

    /// The right-hand side with each point held on the branch of eq. (6) `branches` names
    /// (`true`: loading), continued past eq. (9)'s switch
    /// ([`law::tangential_rate_on_branch`]): smooth in `y`. Fills `lambda` with each point's
    /// `Λ` and `numerator` with eq. (9)'s switching function `N` (NaN where it does not apply).
    pub(crate) fn rate_form_on_branches(
        &self,
        t: f64,
        y: &[f64],
        rate: &mut [f64],
        lambda: &mut [f64],
        branches: &[bool],
        numerator: &mut [f64],
    ) {
        self.rate_form_switched(t, y, rate, lambda, &mut Switching::Held { branches, numerator });
    }

    /// Each point's branch of eq. (6) by eq. (9) at the state `y` at `t` (`true`: loading).
    pub(crate) fn branches(&self, t: f64, y: &[f64], branches: &mut Vec<bool>) {
        let n = self.body.dofs();
        let m = self.contact.points.len();
        let v = &y[n..2 * n];
        branches.clear();
        for surface in &self.contact.surfaces {
            let base = surface.main_body.motion.velocity_at(t);
            for i in surface.points.clone() {
                let point = &self.contact.points[i];
                let v_t = point.tangential.apply(v) - surface.main_body.along(point, base);
                branches.push(law::loads(&surface.params, &self.point_state(y, n, m, i), v_t));
            }
        }
    }

    /// Eq. (9)'s switching function `N` (the numerator of eq. 5) at point `i` for the nodal
    /// velocities `velocity(dof)`, its traction `f_t` and structure `1/R*` at `t`; NaN where
    /// eq. (9) does not apply.
    pub(crate) fn switching_at(
        &self,
        i: usize,
        t: f64,
        velocity: impl Fn(usize) -> f64,
        traction: f64,
        structure: f64,
    ) -> f64 {
        if self.contact.evolves(i) {
            // Switched by eq. (9) at every evaluation (see `rate_form_switched`).
            return f64::NAN;
        }
        let point = &self.contact.points[i];
        let surface = &self.contact.surfaces[point.surface];
        let base = surface.main_body.motion.velocity_at(t);
        let v_t =
            point.tangential.terms().map(|(d, c)| c * velocity(d)).sum::<f64>() - surface.main_body.along(point, base);
        let state =
            ContactState { traction_t: traction, traction_n: self.contact.traction_n[i], structure, plastic_slip: 0.0 };
        law::tangential_rate_on_branch(&surface.params, &state, v_t, false).2
    }

    /// Point `i`'s friction state in the rate form's vector `y` of `n` unknowns and `m` points.
    fn point_state(&self, y: &[f64], n: usize, m: usize, i: usize) -> ContactState {
        ContactState {
            traction_t: y[2 * n + i],
            traction_n: self.contact.traction_n[i],
            structure: y[2 * n + m + i],
            plastic_slip: y[2 * n + 2 * m + i],
        }
    }

    /// The right-hand side switched as `switching` says, compiled for the widest vectors the
    /// processor has (`pulp`'s runtime dispatch), for the friction law's lanes
    /// ([`law::rates_on_branches`]); every width gives the same rates to the bit.
    fn rate_form_switched(&self, t: f64, y: &[f64], rate: &mut [f64], lambda: &mut [f64], switching: &mut Switching) {
        pulp::Arch::new().dispatch(RightHandSide { system: self, t, y, rate, lambda, switching });
    }

    /// [`Self::rate_form_switched`] at one vector width.
    #[inline(always)]
    fn rate_form_at_width(&self, t: f64, y: &[f64], rate: &mut [f64], lambda: &mut [f64], switching: &mut Switching) {
        let n = self.body.dofs();
        let m = self.contact.points.len();
        let (u, rest) = y.split_at(n);
        let (v, rest) = rest.split_at(n);
        let (traction, rest) = rest.split_at(m);
        let (structure, slip) = rest.split_at(m);
        let (du, rest) = rate.split_at_mut(n);
        let (dv, rest) = rest.split_at_mut(n);
        let (dtraction, rest) = rest.split_at_mut(m);
        let (dstructure, dslip) = rest.split_at_mut(m);
        du.copy_from_slice(v);
        // M v̇ = ḟ⁰ t - K u + Σ w Ñᵀ f_t - f_c⁰.
        self.body.stiffness.mul_vec(u, dv);
        self.body.load_at(t).minus(dv, &self.initial_contact_force);
        let (y_contact, rate_contact) = ((traction, structure, slip), (dtraction, dstructure, dslip));
        let mut out = (rate_contact, &mut *lambda);
        for surface in &self.contact.surfaces {
            if surface.normal == NormalBehaviour::Evolving {
                // Switched by eq. (9) at every evaluation; no branch is held over a step.
                if let Switching::Held { numerator, .. } = switching {
                    surface.points.clone().for_each(|i| numerator[i] = f64::NAN);
                }
                self.evolving_contact_rates(surface, t, (u, v), y_contact, &mut out, dv);
                continue;
            }
            match surface.terms {
                1 => self.contact_rates::<1>(surface, (t, v), y_contact, &mut out, dv, switching),
                2 => self.contact_rates::<2>(surface, (t, v), y_contact, &mut out, dv, switching),
                3 => self.contact_rates::<3>(surface, (t, v), y_contact, &mut out, dv, switching),
                _ => self.contact_rates::<4>(surface, (t, v), y_contact, &mut out, dv, switching),
            }
        }
        for (a, mass) in dv.iter_mut().zip(&self.body.mass) {
            *a /= mass;
        }
    }

    /// The contact's part of the right-hand side for one surface whose points read `N` terms
    /// each: the nodal forces `Σ w Ñᵀ f_t` into `dv`, and each point's `ḟ_t` (eq. 6 switched by
    /// eq. 9), `d(1/R*)/dt` (eq. 4) and `ṗ = Λ` (eq. 5), with `Λ` into `out.1`, at time `t` and
    /// nodal velocities `v`.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    fn contact_rates<const N: usize>(
        &self,
        surface: &ContactSurface,
        (t, v): (f64, &[f64]),
        (traction, structure, slip): (&[f64], &[f64], &[f64]),
        ((dtraction, dstructure, dslip), lambda): &mut ((&mut [f64], &mut [f64], &mut [f64]), &mut [f64]),
        dv: &mut [f64],
        switching: &mut Switching,
    ) {
        // A copy of the law's constants: `ln`, called between their uses, might write any memory
        // the compiler can reach (errno), so constants read through `surface` would be loaded
        // again, and `μ_k/μ_s` divided again, at every point.
        let params = &surface.params.clone();
        let (main_body, base) = (&surface.main_body, surface.main_body.motion.velocity_at(t));
        // Every array cut to the surface's points once, so that the loops index them unchecked.
        let range = surface.points.clone();
        let at = SurfacePoints {
            points: &self.contact.points[range.clone()],
            traction_n: &self.contact.traction_n[range.clone()],
            traction: &traction[range.clone()],
            structure: &structure[range.clone()],
            slip: &slip[range.clone()],
        };
        let (dtraction, dstructure) = (&mut dtraction[range.clone()], &mut dstructure[range.clone()]);
        let (dslip, lambda) = (&mut dslip[range.clone()], &mut lambda[range.clone()]);
        match switching {
            Switching::ByEq9 => {
                for k in 0..range.len() {
                    let (state, v_t) = at.point::<N>(k, (main_body, base), v, dv);
                    let (rate, multiplier) = law::tangential_rate_and_multiplier(params, &state, v_t, 0.0);
                    (dtraction[k], dslip[k], lambda[k]) = (rate, multiplier, multiplier);
                    dstructure[k] = law::structure_rate(params, state.structure, multiplier);
                }
            }
            Switching::Held { branches, numerator } => {
                let (branches, numerator) = (&branches[range.clone()], &mut numerator[range.clone()]);
                // `LANES` points at a time through the law, lane by lane; a last, partial group
                // padded with points that transmit nothing (`f_n = 0`), their rates unused.
                for first in (0..range.len()).step_by(LANES) {
                    let count = LANES.min(range.len() - first);
                    let mut points = law::BranchPoints::<LANES>::at_rest();
                    for l in 0..count {
                        let k = first + l;
                        let (state, v_t) = at.point::<N>(k, (main_body, base), v, dv);
                        (points.traction_t[l], points.traction_n[l]) = (state.traction_t, state.traction_n);
                        (points.structure[l], points.v_t[l], points.loading[l]) = (state.structure, v_t, branches[k]);
                    }
                    let rates = law::rates_on_branches(params, &points);
                    for l in 0..count {
                        let k = first + l;
                        (dtraction[k], dslip[k], lambda[k]) =
                            (rates.traction[l], rates.plastic_multiplier[l], rates.plastic_multiplier[l]);
                        (dstructure[k], numerator[k]) = (rates.structure[l], rates.numerator[l]);
                    }
                }
            }
        }
    }

    /// [`Self::contact_rates`] for a surface whose normal traction evolves: each point's `f_n`
    /// from the displacement (`f_n⁰ - α_n (g₀ + n·Ñu)`, [`crate::dynamics::ContactBoundary::normal_traction_at`]),
    /// its normal force beyond `K`'s spring into `dv`, and `ḟ_t` of eq. (6) with the normal
    /// sliding velocity `v̄_n = n·Ñv` in eq. (5)'s numerator. An open point transmits nothing
    /// and its state rests: `ḟ_t = 0`, `d(1/R*)/dt = 0`, `Λ = 0`.
    #[allow(clippy::type_complexity)]
    fn evolving_contact_rates(
        &self,
        surface: &ContactSurface,
        t: f64,
        (u, v): (&[f64], &[f64]),
        (traction, structure, slip): (&[f64], &[f64], &[f64]),
        ((dtraction, dstructure, dslip), lambda): &mut ((&mut [f64], &mut [f64], &mut [f64]), &mut [f64]),
        dv: &mut [f64],
    ) {
        let (params, main_body, contact) = (&surface.params, &surface.main_body, &self.contact);
        let base = main_body.motion.velocity_at(t);
        for i in surface.points.clone() {
            let point = &contact.points[i];
            let f_n = contact.normal_traction_at(i, u);
            point.normal.scatter(contact.normal_correction(i, f_n, u), dv);
            if f_n <= 0.0 {
                (dtraction[i], dstructure[i], dslip[i], lambda[i]) = (0.0, 0.0, 0.0, 0.0);
                continue;
            }
            point.tangential.scatter(point.weight * traction[i], dv);
            let state = ContactState {
                traction_t: traction[i],
                traction_n: f_n,
                structure: structure[i],
                plastic_slip: slip[i],
            };
            let v_t = point.tangential.apply(v) - main_body.along(point, base);
            let (rate, multiplier) = law::tangential_rate_and_multiplier(params, &state, v_t, point.normal.apply(v));
            dtraction[i] = rate;
            dstructure[i] = law::structure_rate(params, structure[i], multiplier);
            dslip[i] = multiplier;
            lambda[i] = multiplier;
        }
    }
}

/// [`System::rate_form_switched`]'s arguments, for `pulp`'s dispatch.
struct RightHandSide<'a, 'b> {
    system: &'a System,
    t: f64,
    y: &'a [f64],
    rate: &'a mut [f64],
    lambda: &'a mut [f64],
    switching: &'a mut Switching<'b>,
}

impl pulp::WithSimd for RightHandSide<'_, '_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<V: pulp::Simd>(self, _: V) {
        self.system.rate_form_at_width(self.t, self.y, self.rate, self.lambda, self.switching);
    }
}

/// One surface's contact points and their friction state in `y`, each cut to the surface's
/// points.
struct SurfacePoints<'a> {
    points: &'a [ContactPoint],
    traction_n: &'a [f64],
    traction: &'a [f64],
    structure: &'a [f64],
    slip: &'a [f64],
}

impl SurfacePoints<'_> {
    /// Point `k`, reading `N` terms: its nodal force `w Ñᵀ f_t` into `dv`, its friction state,
    /// and its relative sliding velocity `v̄_t = Ñ v - v_base` for the main body's velocity
    /// `base`.
    #[inline(always)]
    fn point<const N: usize>(
        &self,
        k: usize,
        (main_body, base): (&MainBody, [f64; 2]),
        v: &[f64],
        dv: &mut [f64],
    ) -> (ContactState, f64) {
        let point = &self.points[k];
        let v_point = point.tangential.scatter_apply_n::<N>(point.weight * self.traction[k], dv, v);
        let state = ContactState {
            traction_t: self.traction[k],
            traction_n: self.traction_n[k],
            structure: self.structure[k],
            plastic_slip: self.slip[k],
        };
        (state, v_point - main_body.along(point, base))
    }
}
