//! Material constants of the super/subloading surface friction model (paper Table 1, MODEL.md).

use serde::Deserialize;

use crate::validate::Checker;

/// Which evolution rule of the degree of structure `1/R*` is integrated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum RStarLaw {
    /// `Ṙ* = κ R*² (1/R* - 1)^m Λ - ξ R*² (1 - μ_k/(μ_s R*))^n`: the form that the paper's
    /// equations (5), (7), (8) are derived from (MODEL.md). The default.
    #[default]
    Consistent,
    /// The paper's equation (4) as printed: both terms divided by `μ_k`. The plastic multiplier
    /// is derived consistently for it too, so the traction stays on the subloading surface.
    Eq4,
}

impl RStarLaw {
    pub fn name(self) -> &'static str {
        match self {
            RStarLaw::Consistent => "consistent",
            RStarLaw::Eq4 => "eq4",
        }
    }
}

/// Friction constants, all SI: tractions in Pa, lengths in m, times in s.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionParams {
    /// Static friction coefficient `μ_s` (-).
    pub mu_s: f64,
    /// Kinetic friction coefficient `μ_k` (-), `0 < μ_k < μ_s`.
    pub mu_k: f64,
    /// Normal elastic modulus of the contact `α_n` (Pa/m). The scenes prescribe the normal
    /// traction, so it enters only the tensors `C^e`, `C^ep` of eqs. (6)-(7).
    pub alpha_n: f64,
    /// Tangential elastic modulus of the contact `α_t` (Pa/m), the penalty stiffness.
    pub alpha_t: f64,
    /// Evolution constant of the normal sliding ratio `R`, `Ṙ = -r ln(R) Λ` (1/m).
    pub r: f64,
    /// Decay constant of the structure by plastic sliding `κ` (1/m).
    pub kappa: f64,
    /// Decay exponent `m` (-).
    pub m: f64,
    /// Healing constant `ξ` (1/s); Table 1 calls it `ζ`.
    pub xi: f64,
    /// Healing exponent `n` (-).
    pub n: f64,
    /// Initial degree of structure `1/R*` (-), in `[1, μ_s/μ_k]`.
    pub structure0: f64,
    /// Magnitude of the initial tangential traction `f_0` (Pa); its direction is the one the
    /// drive loads the contact in.
    pub f0: f64,
    /// Which `R*` evolution rule to integrate.
    #[serde(default)]
    pub rstar_law: RStarLaw,
}

/// How far (relative) `structure0` may exceed the rounded `μ_s/μ_k`: a few units in the last
/// place, so that `structure0 = μ_s/μ_k` computed exactly is accepted.
const STRUCTURE_SLACK: f64 = 4.0 * f64::EPSILON;

impl FrictionParams {
    /// The paper's Table 1 and Table 3 values in SI units (`α = 1000 kPa/m = 1e6 Pa/m`).
    pub fn paper() -> Self {
        Self {
            mu_s: 0.4,
            mu_k: 0.2,
            alpha_n: 1.0e6,
            alpha_t: 1.0e6,
            r: 100.0,
            kappa: 10.0,
            m: 1.0,
            xi: 0.1,
            n: 1.0,
            structure0: 2.0,
            f0: 1.0e-7,
            rstar_law: RStarLaw::Consistent,
        }
    }

    /// The factor `γ` in front of both terms of the `R*` rule: 1, or `1/μ_k` for eq. (4).
    pub fn rstar_scale(&self) -> f64 {
        match self.rstar_law {
            RStarLaw::Consistent => 1.0,
            RStarLaw::Eq4 => 1.0 / self.mu_k,
        }
    }

    /// The ratio `μ_k/μ_s`, the lower bound of `R*`.
    pub fn kinetic_static_ratio(&self) -> f64 {
        self.mu_k / self.mu_s
    }

    /// The initial degree of structure `1/R*₀`: `structure0`, within `[1, μ_s/μ_k]`.
    pub fn initial_structure(&self) -> f64 {
        self.structure0.min(self.max_structure())
    }

    /// The upper bound of the degree of structure, `μ_s/μ_k`.
    pub fn max_structure(&self) -> f64 {
        self.mu_s / self.mu_k
    }

    /// Checks every rule; keys are reported under `checker`'s prefix.
    pub fn check(&self, c: &mut Checker<'_>) {
        c.positive("mu_s", self.mu_s);
        c.positive("mu_k", self.mu_k);
        if self.mu_s.is_finite() && self.mu_k.is_finite() && self.mu_k >= self.mu_s {
            let rule = format!("must be less than {} = {}", c.key("mu_s"), self.mu_s);
            c.fail("mu_k", self.mu_k, rule);
        }
        c.positive("alpha_n", self.alpha_n);
        c.positive("alpha_t", self.alpha_t);
        c.positive("r", self.r);
        c.non_negative("kappa", self.kappa);
        // m = 0 or n = 0 would keep decay (healing) running at the bound 1/R* = 1 (μ_s/μ_k):
        // the model itself would leave its admissible range.
        c.positive("m", self.m);
        c.non_negative("xi", self.xi);
        c.positive("n", self.n);
        c.non_negative("f0", self.f0);
        if c.finite("structure0", self.structure0)
            && self.mu_s.is_finite()
            && self.mu_k.is_finite()
            && self.mu_k > 0.0
            && self.mu_k < self.mu_s
        {
            let max = self.max_structure();
            // μ_s/μ_k rounded may fall a few ulps below the structure0 a user derived from the
            // same two numbers (0.3/0.1 = 2.9999999999999996 against 3): the bound accepts its
            // own exact value, and the initial state takes the rounded bound.
            if !(1.0..=max * (1.0 + STRUCTURE_SLACK)).contains(&self.structure0) {
                let rule = format!(
                    "must lie in [1, {}/{}] = [1, {}] (the degree of structure 1/R*)",
                    c.key("mu_s"),
                    c.key("mu_k"),
                    max
                );
                c.fail("structure0", self.structure0, rule);
            }
        }
    }
}
