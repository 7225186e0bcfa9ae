//! The exponential integral `E1`, and `Ψ` of the normal sliding ratio through it.
//!
//! The evolution rule of the normal sliding ratio, `Ṙ = -r ln(R) Λ` (MODEL.md), integrates in
//! closed form along the plastic slip `p`:
//!
//! `Ψ(R) = ∫₀ᴿ dρ / (-ln ρ) = E1(-ln R)`,  so  `Ψ(R₁) = Ψ(R₀) + r Δp`.
//!
//! `Ψ` maps `[0, 1)` onto `[0, ∞)`, so the update is exact, starts from `R = 0` (the traction
//! reversal every stick-slip cycle passes through) without the `ln 0` singularity, and never lets
//! `R` exceed 1. The update solves for `v = ln(-ln R)`, in which both `R` and `Ψ(R)` are
//! explicit ([`psi_at_ln_u`]), so that no inverse of `E1` is needed.

/// Euler–Mascheroni constant.
const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;

/// `E1(u) = ∫ᵤ^∞ e^{-s}/s ds` for `u ≥ 0` (`E1(0) = ∞`, `E1(∞) = 0`).
pub fn e1(u: f64) -> f64 {
    if u.is_nan() || u < 0.0 {
        return f64::NAN;
    }
    if u == 0.0 {
        return f64::INFINITY;
    }
    e1_by_size(u, || u.ln(), || (-u).exp())
}

/// `E1(u)` for `u > 0` by the expansion its size calls for. `ln_u` and `exp_minus_u` give `ln u`
/// and `e^{-u}`, which only the series and the continued fraction need (a caller may have them).
fn e1_by_size(u: f64, ln_u: impl FnOnce() -> f64, exp_minus_u: impl FnOnce() -> f64) -> f64 {
    if u <= SERIES_LIMIT {
        e1_series(u, ln_u())
    } else if u <= TAYLOR_LIMIT {
        e1_taylor(u)
    } else {
        exp_minus_u() * e1_scaled_continued_fraction(u)
    }
}

/// Below this the power series is used: it converges in at most 20 terms and loses about one
/// digit to cancellation (at 2.5 it would lose two: 2e-14 against mpmath).
const SERIES_LIMIT: f64 = 1.5;

/// From [`SERIES_LIMIT`] to here, Taylor expansions about a grid of centres (see [`e1_taylor`]);
/// above it the continued fraction, which converges in a few dozen terms there but needs
/// hundreds near 2.5 (measured: 230 ns at `u = 2.6` against 30 ns for either expansion).
const TAYLOR_LIMIT: f64 = 24.0;

/// Spacing of the Taylor centres: `|t| ≤ 1/4` from the nearest one.
const TAYLOR_SPACING: f64 = 0.5;

/// `E1` about the nearest centre `c` of a grid on `[SERIES_LIMIT, TAYLOR_LIMIT]`, `u = c + t`:
/// `E1'(u) = -e^{-u}/u = -(e^{-c}/c) g(t)` with `g(t) = e^{-t}/(1 + t/c) = Σ a_k t^k`, where
/// `(1 + t/c) g = e^{-t}` gives `a_k = (-1)^k/k! - a_{k-1}/c`; so
/// `E1(c + t) = E1(c) - (e^{-c}/c) Σ a_k t^{k+1}/(k+1)`.
/// With `|t| ≤ 1/4` and `c ≥ 1.75` the terms fall by 7× each; `E1(c)` comes from the continued
/// fraction once per centre.
fn e1_taylor(u: f64) -> f64 {
    let centres = taylor_centres();
    let index = (((u - SERIES_LIMIT) / TAYLOR_SPACING) as usize).min(centres.len() - 1);
    let centre = &centres[index];
    let t = u - centre.c;
    let mut a = 1.0; // a_0
    let mut t_power = t; // t^{k+1}
    let mut sum = t; // a_0 t
    let mut inverse_factorial = 1.0; // 1/k!, with the sign (-1)^k
    for k in 1..RECIPROCALS.len() - 1 {
        inverse_factorial *= -RECIPROCALS[k];
        a = inverse_factorial - a * centre.inverse_c;
        t_power *= t;
        let term = a * t_power * RECIPROCALS[k + 1];
        sum += term;
        if term.abs() <= 0.5 * f64::EPSILON * sum.abs() {
            break;
        }
    }
    centre.e1_c - centre.slope_scale * sum
}

/// One centre of [`e1_taylor`]'s grid.
struct TaylorCentre {
    c: f64,
    inverse_c: f64,
    e1_c: f64,
    /// `e^{-c}/c`.
    slope_scale: f64,
}

fn taylor_centres() -> &'static [TaylorCentre] {
    static CENTRES: std::sync::OnceLock<Vec<TaylorCentre>> = std::sync::OnceLock::new();
    CENTRES.get_or_init(|| {
        let count = ((TAYLOR_LIMIT - SERIES_LIMIT) / TAYLOR_SPACING).ceil() as usize;
        (0..count)
            .map(|j| {
                let c = SERIES_LIMIT + (j as f64 + 0.5) * TAYLOR_SPACING;
                let e_c = (-c).exp();
                TaylorCentre {
                    c,
                    inverse_c: 1.0 / c,
                    e1_c: e_c * e1_scaled_continued_fraction(c),
                    slope_scale: e_c / c,
                }
            })
            .collect()
    })
}

/// Power series `E1(u) = -γ - ln u - Σ (-u)^k / (k·k!)`, used for `0 < u ≤ SERIES_LIMIT`.
/// `ln_u` is `ln u`, often known already.
fn e1_series(u: f64, ln_u: f64) -> f64 {
    let mut sum = 0.0;
    let mut term = 1.0; // (-u)^k / k!
    for &inverse_k in &RECIPROCALS[1..] {
        term *= -u * inverse_k;
        let contribution = term * inverse_k;
        sum += contribution;
        if contribution.abs() <= f64::EPSILON * sum.abs() {
            break;
        }
    }
    -EULER_GAMMA - ln_u - sum
}

/// `1/k` for the series terms (a product is several times faster than a division).
const RECIPROCALS: [f64; 60] = {
    let mut table = [0.0; 60];
    let mut k = 1;
    while k < 60 {
        table[k] = 1.0 / k as f64;
        k += 1;
    }
    table
};

/// `e^u E1(u)` by the continued fraction (modified Lentz): above `TAYLOR_LIMIT`, and once for each
/// Taylor centre.
fn e1_scaled_continued_fraction(u: f64) -> f64 {
    const TINY: f64 = 1e-300;
    let mut b = u + 1.0;
    let mut c = 1.0 / TINY;
    let mut d = 1.0 / b;
    let mut h = d;
    for i in 1..500 {
        let a = -((i * i) as f64);
        b += 2.0;
        d = 1.0 / (a * d + b);
        c = b + a / c;
        let delta = c * d;
        h *= delta;
        if (delta - 1.0).abs() <= f64::EPSILON {
            break;
        }
    }
    h
}

/// `(u, R, Ψ(R))` for `u = e^v`, `R = e^{-u}`: the sliding ratio and its `Ψ = E1(u)`, without
/// a logarithm (the series takes `ln u = v` as it is).
pub fn psi_at_ln_u(v: f64) -> (f64, f64, f64) {
    let u = v.exp();
    let ratio = (-u).exp();
    (u, ratio, e1_by_size(u, || v, || ratio))
}

/// `Ψ(R) = E1(-ln R)`, the integral of the `R` evolution rule (see the module docs).
pub fn psi(sliding_ratio: f64) -> f64 {
    if sliding_ratio <= 0.0 {
        0.0
    } else if sliding_ratio >= 1.0 {
        f64::INFINITY
    } else {
        e1(-sliding_ratio.ln())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference values of E1 (Abramowitz & Stegun Table 5.1; 30 digits from mpmath.e1).
    #[test]
    fn e1_matches_tabulated_values() {
        let table = [
            (0.1, 1.822_923_958_419_390_6),
            (0.5, 0.559_773_594_776_160_8),
            (1.0, 0.219_383_934_395_520_3),
            (1.2, 0.158_408_436_851_462_57),
            (1.5, 0.100_019_582_406_632_65),
            (1.75, 0.069_488_684_604_638_79),
            (2.0, 0.048_900_510_708_061_12),
            (2.25, 0.034_762_073_119_444_6),
            (2.5, 0.024_914_917_870_269_735),
            (2.6, 0.021_850_221_804_082_191),
            (3.0, 0.013_048_381_094_197_037),
            (4.0, 0.003_779_352_409_848_906_5),
            (5.0, 0.001_148_295_591_275_325_8),
            (7.5, 6.583_089_326_708_023e-5),
            (10.0, 4.156_968_929_685_324e-6),
            (15.0, 1.918_627_892_147_867e-8),
            (19.9, 1.092_215_649_960_176e-10),
        ];
        for (u, expected) in table {
            let got = e1(u);
            assert!((got - expected).abs() <= 1e-14 * expected, "E1({u}) = {got}, expected {expected}");
        }
    }

    /// The Taylor grid on every centre's whole interval (edges included) against an independent
    /// evaluation, the continued fraction, from 2.5 up where it is accurate to a few ulps. Below
    /// 2.5 the tabulated values above cover two centres at their middles and edges.
    #[test]
    fn taylor_grid_matches_the_continued_fraction() {
        let mut worst = 0.0_f64;
        let mut u = 2.5;
        while u <= TAYLOR_LIMIT {
            let reference = (-u).exp() * e1_scaled_continued_fraction(u);
            worst = worst.max((e1_taylor(u) - reference).abs() / reference);
            u += TAYLOR_SPACING / 64.0;
        }
        assert!(worst <= 4e-15, "worst relative difference {worst:e}");
    }

    #[test]
    fn psi_at_ln_u_matches_psi_over_the_whole_range() {
        // v = ln(-ln R) from R = 1 - 1e-300 to R = e^-700: every branch of E1.
        let mut v = -690.0_f64;
        while v <= 6.55 {
            let (u, ratio, value) = psi_at_ln_u(v);
            assert!((u - v.exp()).abs() <= 1e-15 * u, "v = {v}: u = {u}");
            assert!((ratio - (-u).exp()).abs() <= 1e-15 * ratio, "v = {v}: R = {ratio}");
            let expected = e1(u);
            assert!((value - expected).abs() <= 1e-15 * expected, "v = {v}: Ψ = {value}, E1(u) = {expected}");
            v += 0.37;
        }
    }
}
