//! The exponential integral `E1` and its inverse.
//!
//! The evolution rule of the normal sliding ratio, `Ṙ = -r ln(R) Λ` (MODEL.md), integrates in
//! closed form along the plastic slip `p`:
//!
//! `Ψ(R) = ∫₀ᴿ dρ / (-ln ρ) = E1(-ln R)`,  so  `Ψ(R₁) = Ψ(R₀) + r Δp`.
//!
//! `Ψ` maps `[0, 1)` onto `[0, ∞)`, so the update is exact, starts from `R = 0` (the traction
//! reversal every stick-slip cycle passes through) without the `ln 0` singularity, and never lets
//! `R` exceed 1.

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
    if u <= SERIES_LIMIT {
        e1_series(u, u.ln())
    } else if u <= TAYLOR_LIMIT {
        e1_taylor(u)
    } else {
        (-u).exp() * e1_scaled_continued_fraction(u)
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

/// `ln E1(u)`, accurate where `E1(u)` itself would underflow (large `u`).
pub fn ln_e1(u: f64) -> f64 {
    if u.is_infinite() { f64::NEG_INFINITY } else { ln_e1_and_scaled(u, u.ln()).0 }
}

/// `(ln E1(u), e^u E1(u), e^{-u})` for `0 < u < ∞` by one evaluation; `ln_u` is `ln u`.
fn ln_e1_and_scaled(u: f64, ln_u: f64) -> (f64, f64, f64) {
    let ratio = (-u).exp();
    if u <= TAYLOR_LIMIT {
        let value = if u <= SERIES_LIMIT { e1_series(u, ln_u) } else { e1_taylor(u) };
        (value.ln(), value / ratio, ratio)
    } else {
        let scaled = e1_scaled_continued_fraction(u);
        (-u + scaled.ln(), scaled, ratio)
    }
}

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

/// A solution of `E1(u) = y`, kept so that the next inversion at a nearby `y` can start from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct E1Root {
    /// `u ≥ 0` with `E1(u) = y`.
    pub u: f64,
    /// `e^{-u}`: the sliding ratio `R` when `y = Ψ(R)`.
    pub ratio: f64,
    /// `ln u`.
    ln_u: f64,
    /// `ln y`.
    ln_y: f64,
    /// `e^u E1(u)`, i.e. `-1 / (d ln E1 / d ln u)` at the root.
    scaled: f64,
}

/// The inverse of `E1`: the `u ≥ 0` with `E1(u) = y`, for `y ≥ 0` (`y = 0 → ∞`, `y = ∞ → 0`).
pub fn e1_inverse(y: f64) -> f64 {
    e1_inverse_near(y, None).u
}

/// Stop once a Newton step in `ln u` is this small: convergence is quadratic with a curvature
/// factor below 1, so the stepped-to iterate is then accurate to rounding.
const QUADRATIC_STOP: f64 = 1e-8;

/// [`e1_inverse`] starting from the root at a nearby `y` when one is known (a previous iterate):
/// the first Newton step then needs no evaluation, and one or two more finish.
///
/// Newton on `h(v) = ln E1(e^v) - ln y` in `v = ln u`, where `h` is smooth and strictly
/// decreasing on the whole real line, safeguarded by bisection.
pub fn e1_inverse_near(y: f64, near: Option<E1Root>) -> E1Root {
    let at = |u: f64, scaled: f64| E1Root { u, ratio: (-u).exp(), ln_u: u.ln(), ln_y: y.ln(), scaled };
    if y.is_nan() || y < 0.0 {
        return at(f64::NAN, f64::NAN);
    }
    if y == 0.0 {
        return at(f64::INFINITY, 0.0);
    }
    if y.is_infinite() {
        return at(0.0, f64::INFINITY);
    }
    let ln_y = y.ln();
    // Bracket in v = ln u. E1(e^-745) ≈ 745 - γ and E1(e^6.7) ≈ e^-812 cover every finite double.
    let (mut lo, mut hi) = (-745.0_f64, 6.7_f64);
    let mut v = match near {
        // h(v_near) = ln y_near - ln y and h'(v_near) = -1/scaled_near: a Newton step for free.
        Some(root) if root.ln_u.is_finite() && root.scaled.is_finite() => {
            (root.ln_u + (root.ln_y - ln_y) * root.scaled).clamp(lo, hi)
        }
        // E1(u) ≈ -γ - ln u for small u; for large u, E1(u) ≈ e^-u/(u + 1), so
        // u = -ln y - ln(u + 1) by a few fixed-point sweeps.
        _ if y > 0.5 => (-EULER_GAMMA - y).max(-744.0),
        _ => {
            let mut u0 = -ln_y;
            for _ in 0..4 {
                u0 = (-ln_y - (u0 + 1.0).ln()).max(1e-3);
            }
            u0.ln()
        }
    };
    for _ in 0..200 {
        let u = v.exp();
        // One evaluation gives ln E1(u), the slope dh/dv = -1 / (e^u E1(u)) and e^{-u}.
        let (ln_e1_u, scaled, ratio) = ln_e1_and_scaled(u, v);
        let h = ln_e1_u - ln_y;
        // ln E1 carries a rounding error of a few ulps of |ln y|: below that, h is noise.
        if h.abs() <= 4.0 * f64::EPSILON * ln_y.abs().max(1.0) {
            return E1Root { u, ratio, ln_u: v, ln_y, scaled };
        }
        // h is decreasing in v: h > 0 means the root lies to the right.
        if h > 0.0 {
            lo = v;
        } else {
            hi = v;
        }
        let newton = v + h * scaled;
        let next = if newton.is_finite() && newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
        let step = (next - v).abs();
        if step <= 4.0 * f64::EPSILON * v.abs().max(1.0) || (next == newton && step <= QUADRATIC_STOP) {
            // The slope barely changes over so short a step.
            let u = next.exp();
            return E1Root { u, ratio: (-u).exp(), ln_u: next, ln_y, scaled };
        }
        v = next;
    }
    let u = v.exp();
    E1Root { u, ratio: (-u).exp(), ln_u: v, ln_y, scaled: f64::NAN }
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

/// The inverse of [`psi`]: the sliding ratio `R ∈ [0, 1]` with `Ψ(R) = y`, together with the
/// root `u = -ln R` (which keeps full precision where `R` rounds to 1). `near` is the root at a
/// nearby `y`, if known.
pub fn psi_inverse(y: f64, near: Option<E1Root>) -> (f64, E1Root) {
    let root = e1_inverse_near(y, near);
    (root.ratio, root)
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
    fn e1_inverse_round_trips_over_the_whole_range() {
        for exponent in -300..=2 {
            for mantissa in [1.0, 2.5, 7.0] {
                let u = mantissa * 10f64.powi(exponent);
                if u > 700.0 {
                    continue;
                }
                let y = e1(u);
                let back = e1_inverse(y);
                assert!((back - u).abs() <= 1e-12 * u, "u = {u}: E1 = {y}, inverse = {back}");
            }
        }
    }
}
