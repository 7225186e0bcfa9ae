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
    if u <= SERIES_LIMIT { e1_series(u) } else { (-u).exp() * e1_scaled_continued_fraction(u) }
}

/// Below this the power series is used, above it the continued fraction: both converge in a
/// few dozen terms there.
const SERIES_LIMIT: f64 = 2.5;

/// `ln E1(u)`, accurate where `E1(u)` itself would underflow (large `u`).
pub fn ln_e1(u: f64) -> f64 {
    if u <= SERIES_LIMIT {
        e1(u).ln()
    } else if u.is_infinite() {
        f64::NEG_INFINITY
    } else {
        -u + e1_scaled_continued_fraction(u).ln()
    }
}

/// Power series `E1(u) = -γ - ln u - Σ (-u)^k / (k·k!)`, used for `0 < u ≤ 2.5`.
fn e1_series(u: f64) -> f64 {
    let mut sum = 0.0;
    let mut term = 1.0; // (-u)^k / k!
    for k in 1..60 {
        term *= -u / k as f64;
        let contribution = term / k as f64;
        sum += contribution;
        if contribution.abs() <= f64::EPSILON * sum.abs() {
            break;
        }
    }
    -EULER_GAMMA - u.ln() - sum
}

/// `e^u E1(u)` by the continued fraction (modified Lentz), used for `u > 2.5`.
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

/// The inverse of `E1`: the `u ≥ 0` with `E1(u) = y`, for `y ≥ 0` (`y = 0 → ∞`, `y = ∞ → 0`).
pub fn e1_inverse(y: f64) -> f64 {
    e1_inverse_near(y, None)
}

/// [`e1_inverse`] starting from `guess` when one is known (a previous iterate): Newton then
/// needs one or two steps.
///
/// Newton on `h(v) = ln E1(e^v) - ln y` in `v = ln u`, where `h` is smooth and strictly
/// decreasing on the whole real line, safeguarded by bisection.
pub fn e1_inverse_near(y: f64, guess: Option<f64>) -> f64 {
    if y.is_nan() || y < 0.0 {
        return f64::NAN;
    }
    if y == 0.0 {
        return f64::INFINITY;
    }
    if y.is_infinite() {
        return 0.0;
    }
    let ln_y = y.ln();
    // Bracket in v = ln u. E1(e^-745) ≈ 745 - γ and E1(e^6.7) ≈ e^-812 cover every finite double.
    let (mut lo, mut hi) = (-745.0_f64, 6.7_f64);
    let mut v = match guess {
        Some(u) if u > 0.0 && u.is_finite() => u.ln().clamp(lo, hi),
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
        // One evaluation gives both ln E1(u) and the slope dh/dv = -1 / (e^u E1(u)).
        let (ln_e1_u, scaled) = if u <= SERIES_LIMIT {
            let value = e1_series(u);
            (value.ln(), u.exp() * value)
        } else {
            let scaled = e1_scaled_continued_fraction(u);
            (-u + scaled.ln(), scaled)
        };
        let h = ln_e1_u - ln_y;
        // ln E1 carries a rounding error of a few ulps of |ln y|: below that, h is noise.
        if h.abs() <= 4.0 * f64::EPSILON * ln_y.abs().max(1.0) {
            return u;
        }
        // h is decreasing in v: h > 0 means the root lies to the right.
        if h > 0.0 {
            lo = v;
        } else {
            hi = v;
        }
        let mut next = v + h * scaled;
        if !next.is_finite() || next <= lo || next >= hi {
            next = 0.5 * (lo + hi);
        }
        if (next - v).abs() <= 4.0 * f64::EPSILON * v.abs().max(1.0) {
            return next.exp();
        }
        v = next;
    }
    v.exp()
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

/// The inverse of [`psi`]: the sliding ratio `R ∈ [0, 1]` with `Ψ(R) = y`, together with
/// `-ln R` (which keeps full precision where `R` rounds to 1). `near` is a guess of `-ln R`.
pub fn psi_inverse(y: f64, near: Option<f64>) -> (f64, f64) {
    let u = e1_inverse_near(y, near);
    ((-u).exp(), u)
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
            (2.0, 0.048_900_510_708_061_12),
            (10.0, 4.156_968_929_685_324e-6),
        ];
        for (u, expected) in table {
            let got = e1(u);
            assert!((got - expected).abs() <= 1e-14 * expected, "E1({u}) = {got}, expected {expected}");
        }
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
