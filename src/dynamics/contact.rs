//! The contact force boundary `S_c`: Gauss points that carry friction states (paper §2.2).
//!
//! A contact is a curve of the body (the paper's counter body) pressed against a rigid main
//! body (the moving base). At each Gauss point the unit tangent `t` and normal `n` come from the curve: `n`
//! points from the main body into the body, `t` is `n` turned clockwise by a right angle,
//! so the body lies on the left of `t` (docs/model.md, "Bodies, normal and signs"). Every
//! traction and slip of the friction law is along this local frame.

use crate::dynamics::motion::Motion;
use crate::friction::FrictionParams;

/// A linear combination of degrees of freedom, `Σ c_k u[d_k]`: how a contact point reads a
/// component of the body's displacement along a direction. Terms with a zero factor are not
/// stored, so a contact along x reads only x degrees of freedom, in the order given.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Projection {
    dofs: [usize; 4],
    factors: [f64; 4],
    len: usize,
}

impl Projection {
    /// `Σ factor · u[dof]` over `terms`, at most four; zero factors are dropped.
    pub fn new(terms: impl IntoIterator<Item = (usize, f64)>) -> Self {
        let mut projection = Self::default();
        for (dof, factor) in terms {
            if factor != 0.0 {
                assert!(projection.len < 4, "a contact point reads at most two nodes of two components");
                projection.dofs[projection.len] = dof;
                projection.factors[projection.len] = factor;
                projection.len += 1;
            }
        }
        projection
    }

    /// `Σ c_k field[d_k]`, summed in the order of the terms.
    #[inline]
    pub fn apply(&self, field: &[f64]) -> f64 {
        match self.len {
            0 => 0.0,
            len => (1..len)
                .fold(self.factors[0] * field[self.dofs[0]], |sum, k| sum + self.factors[k] * field[self.dofs[k]]),
        }
    }

    /// `forces[d_k] += scale · c_k`: the transpose of [`Self::apply`].
    #[inline]
    pub fn scatter(&self, scale: f64, forces: &mut [f64]) {
        for k in 0..self.len {
            forces[self.dofs[k]] += scale * self.factors[k];
        }
    }

    /// [`Self::scatter`] of `scale` into `forces` and [`Self::apply`] of `field` for a
    /// projection of `N` terms (padded to it, [`Self::padded`]), in one pass over the terms,
    /// the loop unrolled: each index is checked once, `forces` cut to `field`'s length. The
    /// same sums as the two apart. The rate form's right-hand side reads every point this way.
    #[inline(always)]
    pub fn scatter_apply_n<const N: usize>(&self, scale: f64, forces: &mut [f64], field: &[f64]) -> f64 {
        let forces = &mut forces[..field.len()];
        let mut sum = 0.0;
        for k in 0..N {
            let (dof, factor) = (self.dofs[k], self.factors[k]);
            let term = factor * field[dof];
            sum = if k == 0 { term } else { sum + term };
            forces[dof] += scale * factor;
        }
        sum
    }

    /// Number of terms.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether it reads nothing.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The same projection with `n` terms: the missing ones read its first degree of freedom
    /// with a factor `+0`, which adds nothing to a sum (a zero of the sign of the other terms'
    /// products, or of the sum's) except the sign of an exact zero.
    pub fn padded(&self, n: usize) -> Self {
        let mut out = *self;
        for k in self.len..n {
            out.dofs[k] = self.dofs[0];
            out.factors[k] = 0.0;
        }
        out.len = n.max(self.len);
        out
    }

    /// The `(dof, factor)` terms.
    pub fn terms(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        (0..self.len).map(|k| (self.dofs[k], self.factors[k]))
    }

    /// The same projection with its degrees of freedom renumbered by `map`.
    pub fn renumbered(&self, map: impl Fn(usize) -> usize) -> Self {
        let mut out = *self;
        for k in 0..self.len {
            out.dofs[k] = map(self.dofs[k]);
        }
        out
    }
}

/// One integration point of the contact boundary. Its relative tangential displacement is
/// `ū_t = t · Σ_a N_a u_a - t · u_base` (eq. 12 with the shape functions `Ñ` of eq. 13), and it
/// contributes `weight · Ñᵀ f_t t` to the nodal forces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// `t · Σ N_a u_a`: the body's displacement along the tangent at the point.
    pub tangential: Projection,
    /// `n · Σ N_a u_a`: along the normal.
    pub normal: Projection,
    /// Integration weight: Gauss weight × Jacobian (m per unit thickness), or 1 per unit area.
    pub weight: f64,
    /// The contact surface the point belongs to ([`ContactBoundary::surfaces`]).
    pub surface: usize,
    /// Unit tangent `t` (global x, y).
    pub tangent: [f64; 2],
    /// Direction (±1) in which the drive first loads `f_t`: the sign of the initial traction `f0`.
    pub loading_direction: f64,
}

impl ContactPoint {
    /// A point that follows a single degree of freedom with unit weight (per unit area).
    pub fn single(dof: usize, loading_direction: f64) -> Self {
        Self {
            tangential: Projection::new([(dof, 1.0)]),
            normal: Projection::default(),
            weight: 1.0,
            surface: 0,
            tangent: [1.0, 0.0],
            loading_direction,
        }
    }

    /// `t · Σ_a N_a field_a`.
    #[inline]
    pub fn interpolate(&self, field: &[f64]) -> f64 {
        self.tangential.apply(field)
    }

    /// `forces += scale · Ñᵀ t`.
    #[inline]
    pub fn scatter(&self, scale: f64, forces: &mut [f64]) {
        self.tangential.scatter(scale, forces);
    }
}

/// How a contact's main body moves.
#[derive(Debug, Clone, PartialEq)]
pub struct MainBody {
    /// Its velocity history (m/s).
    pub motion: Motion,
    /// Whether [`Self::motion`]'s first component is a speed along each point's tangent (the
    /// block's base, sliding along its contact) rather than a velocity in x and y.
    pub along_tangent: bool,
}

impl MainBody {
    /// Held still.
    pub fn at_rest() -> Self {
        Self { motion: Motion::at_rest(), along_tangent: true }
    }

    /// The component of a velocity or displacement `value` of the main body along `point`'s
    /// tangent.
    #[inline]
    pub fn along(&self, point: &ContactPoint, value: [f64; 2]) -> f64 {
        if self.along_tangent { value[0] } else { point.tangent[0] * value[0] + point.tangent[1] * value[1] }
    }
}

/// How a contact's normal traction behaves (the case key `normal`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NormalBehaviour {
    /// Prescribed and held constant in time (the paper's §3.2): the friction law sees its
    /// initial value whatever the body does. The default.
    #[default]
    Held,
    /// `ḟ_n = -α_n v̄_n` from its initial value: `f_n = f_n⁰ - α_n (g₀ + ū_n)` while that is
    /// positive, and the contact is open (both tractions zero) where it is not.
    Evolving,
}

impl NormalBehaviour {
    pub fn name(self) -> &'static str {
        match self {
            NormalBehaviour::Held => "held",
            NormalBehaviour::Evolving => "evolving",
        }
    }
}

/// One frictional contact: its law, its main body and how its normal traction behaves.
#[derive(Debug, Clone)]
pub struct ContactSurface {
    pub params: FrictionParams,
    pub main_body: MainBody,
    pub normal: NormalBehaviour,
    /// Its points, contiguous in [`ContactBoundary::points`].
    pub points: std::ops::Range<usize>,
    /// How many terms each of its points' tangential projections has (padded to the most).
    pub terms: usize,
}

/// The frictional boundary: its surfaces, their points and the points' normal tractions.
#[derive(Debug, Clone)]
pub struct ContactBoundary {
    pub surfaces: Vec<ContactSurface>,
    pub points: Vec<ContactPoint>,
    /// Normal traction `f_n ≥ 0` at each point (Pa): held constant, or the initial value of an
    /// evolving one.
    pub traction_n: Vec<f64>,
    /// Each point's initial normal gap `g₀ ≥ 0` (m): 0 where it is pressed, and at every point
    /// of a held contact.
    pub gap: Vec<f64>,
}

impl ContactBoundary {
    /// One surface of law `params` and main body `main_body` holding every point.
    pub fn single(
        params: FrictionParams,
        main_body: MainBody,
        points: Vec<ContactPoint>,
        traction_n: Vec<f64>,
    ) -> Self {
        let (points, terms) = padded(points);
        let gap = vec![0.0; points.len()];
        Self {
            surfaces: vec![ContactSurface {
                params,
                main_body,
                normal: NormalBehaviour::Held,
                points: 0..points.len(),
                terms,
            }],
            points,
            traction_n,
            gap,
        }
    }

    /// Whether point `k`'s normal traction evolves.
    #[inline]
    pub fn evolves(&self, k: usize) -> bool {
        self.surfaces[self.points[k].surface].normal == NormalBehaviour::Evolving
    }

    /// Whether any contact's normal traction evolves.
    pub fn any_evolving(&self) -> bool {
        self.surfaces.iter().any(|s| s.normal == NormalBehaviour::Evolving)
    }

    /// The normal traction the contact's elastic spring gives point `k` at the displacement
    /// `u` (from the initial equilibrium): `f_n⁰ - α_n (g₀ + n·Ñu)`, eq. (6)'s `ḟ_n = -α_n v̄_n`
    /// integrated exactly. Not positive where the point is open.
    #[inline]
    pub fn normal_trial(&self, k: usize, u: &[f64]) -> f64 {
        self.traction_n[k] - self.params(k).alpha_n * (self.gap[k] + self.points[k].normal.apply(u))
    }

    /// `f_n = max(0, trial)` of an evolving point at `u` ([`Self::normal_trial`]).
    #[inline]
    pub fn normal_traction_at(&self, k: usize, u: &[f64]) -> f64 {
        self.normal_trial(k, u).max(0.0)
    }

    /// The normal force of evolving point `k` beyond what `K`'s linear spring `-α_n w n·Ñu`
    /// and the initial equilibrium's `f_n⁰` already give, for its normal traction `f_n` at `u`:
    /// `w (f_n - f_n⁰ + α_n n·Ñu)`, to be scattered along `n·Ñ`. Zero while the point stays
    /// pressed as it started; while it is open, it takes the spring and `f_n⁰` away.
    #[inline]
    pub fn normal_correction(&self, k: usize, traction_n: f64, u: &[f64]) -> f64 {
        let point = &self.points[k];
        point.weight * (traction_n - self.traction_n[k] + self.params(k).alpha_n * point.normal.apply(u))
    }

    /// `-w α_n` for an open evolving point, 0 otherwise: the change of Newton's operator
    /// `K + K_c` along its `n·Ñ` ([`Self::normal_correction`]'s slope, negated).
    #[inline]
    pub fn normal_stiffness(&self, k: usize, traction_n: f64) -> f64 {
        if self.evolves(k) && traction_n <= 0.0 { -self.points[k].weight * self.params(k).alpha_n } else { 0.0 }
    }

    /// Adds every evolving point's [`Self::normal_correction`] at `u` to `forces` and returns
    /// the points' normal tractions there (empty without evolving points).
    pub fn scatter_normal_corrections(&self, u: &[f64], forces: &mut [f64]) -> Vec<f64> {
        if !self.any_evolving() {
            return Vec::new();
        }
        (0..self.points.len())
            .map(|k| {
                if !self.evolves(k) {
                    return self.traction_n[k];
                }
                let f_n = self.normal_traction_at(k, u);
                self.points[k].normal.scatter(self.normal_correction(k, f_n, u), forces);
                f_n
            })
            .collect()
    }

    /// The potential of evolving point `k`'s [`Self::normal_correction`] at `u`, so that `K`'s
    /// strain energy plus it is the contact's normal spring energy: with `x = n·Ñu`,
    /// `f_r = f_n⁰ - α_n g₀`, `w [(max(0, f_r - α_n x)² - max(0, f_r)²)/(2α_n) + f_n⁰ x - α_n x²/2]`
    /// (J per unit thickness). Zero while the point stays pressed.
    pub fn normal_potential(&self, k: usize, u: &[f64]) -> f64 {
        if !self.evolves(k) {
            return 0.0;
        }
        let (point, alpha_n) = (&self.points[k], self.params(k).alpha_n);
        let x = point.normal.apply(u);
        let reference = self.traction_n[k] - alpha_n * self.gap[k];
        let now = (reference - alpha_n * x).max(0.0);
        let start = reference.max(0.0);
        point.weight * ((now * now - start * start) / (2.0 * alpha_n) + self.traction_n[k] * x - 0.5 * alpha_n * x * x)
    }

    /// The friction law of point `k`.
    #[inline]
    pub fn params(&self, k: usize) -> &FrictionParams {
        &self.surfaces[self.points[k].surface].params
    }

    /// Each surface's main-body velocity at `t`, for [`Self::base_along`].
    pub fn base_velocities(&self, t: f64) -> SurfaceValues {
        SurfaceValues::of(&self.surfaces, |s| s.main_body.motion.velocity_at(t))
    }

    /// Each surface's main-body displacement from `t0` to `t1`, for [`Self::base_along`] (the
    /// same projection applies).
    pub fn base_increments(&self, t0: f64, t1: f64) -> SurfaceValues {
        SurfaceValues::of(&self.surfaces, |s| {
            let (a, b) = (s.main_body.motion.displacement_at(t1), s.main_body.motion.displacement_at(t0));
            [a[0] - b[0], a[1] - b[1]]
        })
    }

    /// The main body's velocity (or displacement) along point `k`'s tangent, from the
    /// surfaces' values `per_surface` ([`Self::base_velocities`], [`Self::base_increments`]).
    #[inline]
    pub fn base_along(&self, k: usize, per_surface: &SurfaceValues) -> f64 {
        self.base_along_point(&self.points[k], per_surface)
    }

    /// [`Self::base_along`] for a point at hand.
    #[inline]
    pub fn base_along_point(&self, point: &ContactPoint, per_surface: &SurfaceValues) -> f64 {
        self.surfaces[point.surface].main_body.along(point, per_surface.get(point.surface))
    }

    /// The main bodies' displacement from `t0` to `t1` along each point's tangent (m).
    pub fn base_slips(&self, t0: f64, t1: f64) -> Vec<f64> {
        let bases = self.base_increments(t0, t1);
        (0..self.points.len()).map(|k| self.base_along(k, &bases)).collect()
    }

    /// The largest speed of any main body (m/s).
    pub fn largest_base_speed(&self) -> f64 {
        self.surfaces.iter().map(|s| s.main_body.motion.largest_speed()).fold(0.0, f64::max)
    }
}

/// A value per contact surface (a main body's velocity or displacement increment), kept
/// without allocating for the usual single surface: the right-hand side of the rate form
/// asks for it at every stage.
pub struct SurfaceValues {
    first: [f64; 2],
    rest: Vec<[f64; 2]>,
}

impl SurfaceValues {
    fn of(surfaces: &[ContactSurface], value: impl Fn(&ContactSurface) -> [f64; 2]) -> Self {
        let mut values = surfaces.iter().map(value);
        Self { first: values.next().unwrap_or([0.0, 0.0]), rest: values.collect() }
    }

    /// The value of surface `s`.
    #[inline]
    pub fn get(&self, s: usize) -> [f64; 2] {
        if s == 0 { self.first } else { self.rest[s - 1] }
    }
}

/// `points` with their tangential projections padded to the most terms any has, and that
/// number (at least 1).
pub fn padded(mut points: Vec<ContactPoint>) -> (Vec<ContactPoint>, usize) {
    let terms = points.iter().map(|p| p.tangential.len()).max().unwrap_or(1).max(1);
    for p in &mut points {
        p.tangential = p.tangential.padded(terms);
    }
    (points, terms)
}
