//! Tsitouras' explicit 5(4) pair (Ch. Tsitouras, "Runge–Kutta pairs of order 5(4) satisfying
//! only the first column simplifying assumption", Comput. Math. Appl. 62 (2011) 770–775,
//! Table 1): its tableau as data, and one step with the embedded error estimate.

use crate::dynamics::control::ErrorScaling;

/// Nodes `c_2 … c_7` (Tsitouras 2011, Table 1).
const C: [f64; 6] = [0.161, 0.327, 0.9, 0.980_025_540_904_509_7, 1.0, 1.0];

/// Coefficients `a_ij` of stages 2 … 7; the last row is the fifth-order solution's weights `b`.
const A: [[f64; 6]; 6] = [
    [0.161, 0.0, 0.0, 0.0, 0.0, 0.0],
    [-0.008_480_655_492_356_989, 0.335_480_655_492_357, 0.0, 0.0, 0.0, 0.0],
    [2.897_153_057_105_493_5, -6.359_448_489_975_075, 4.362_295_432_869_581_5, 0.0, 0.0, 0.0],
    [5.325_864_828_439_257, -11.748_883_564_062_828, 7.495_539_342_889_836_5, -0.092_495_066_361_755_25, 0.0, 0.0],
    [
        5.861_455_442_946_42,
        -12.920_969_317_847_11,
        8.159_367_898_576_159,
        -0.071_584_973_281_401,
        -0.028_269_050_394_068_383,
        0.0,
    ],
    [
        0.096_460_766_818_065_23,
        0.01,
        0.479_889_650_414_499_6,
        1.379_008_574_103_742,
        -3.290_069_515_436_081,
        2.324_710_524_099_774,
    ],
];

/// `b - b̂`: the difference of the fifth- and fourth-order solutions, per stage.
const ERROR: [f64; 7] = [
    -0.001_780_011_052_225_777,
    -0.000_816_434_459_656_746_9,
    0.007_880_878_010_261_995,
    -0.144_711_007_173_262_9,
    0.582_357_165_452_555_2,
    -0.458_082_105_929_186_97,
    1.0 / 66.0,
];

/// The pair's continuous extension: the weights `b_i(θ) = Σ_k r_ik θ^k` (`k = 1 … 4`) of its
/// fourth-order dense output `y(t + θh) = y + h Σ_i b_i(θ) k_i` (Tsitouras 2011, §3; the
/// coefficients as OrdinaryDiffEq.jl's `Tsit5Interp` gives them). At `θ = 1` they are `b`.
const DENSE: [[f64; 4]; 7] = [
    [1.0, -2.763_706_197_274_826, 2.913_255_461_821_912_6, -1.053_088_497_729_021_6],
    [0.0, 0.131_699_999_999_999_98, -0.223_4, 0.101_7],
    [0.0, 3.930_296_236_894_751_6, -5.941_033_872_131_505, 2.490_627_285_651_253],
    [0.0, -12.411_077_166_933_676, 30.338_188_630_282_32, -16.548_102_889_244_902],
    [0.0, 37.509_313_416_511_04, -88.178_904_894_766_4, 47.379_521_962_819_28],
    [0.0, -27.896_526_289_197_286, 65.091_894_674_793_66, -34.870_657_861_496_61],
    [0.0, 1.5, -4.0, 2.5],
];

/// The dense output's weights `b_i(θ)` at `θ` ([`DENSE`]).
pub fn dense_weights(theta: f64) -> [f64; 7] {
    DENSE.map(|[r1, r2, r3, r4]| theta * (r1 + theta * (r2 + theta * (r3 + theta * r4))))
}

/// The extent of the pair's stability region along the imaginary axis: `|R(iy)| ≤ 1` for
/// `|y| ≤ 0.47798` (the first crossing of 1 by [`amplification`]; `|R(iy)| - 1 ≈ -4e-5 y⁶`
/// below it), rounded down. Beyond it every undamped mode grows a little at every step:
/// `|R(iy)| = 1.00013` at `y = 1`, 1.026 at 2, 1.28 at 3.
pub const IMAGINARY_STABILITY: f64 = 0.4779;

/// `|R(iy)|`: the factor by which one step of `h` multiplies the amplitude of an undamped mode
/// of frequency `ω = y/h`. `R(z)` is the pair's stability function, `R(z) = Y₇` from the stage
/// recursion `Yᵢ = 1 + z Σⱼ aᵢⱼ Yⱼ` of `ẏ = λy` (`z = hλ`) over the tableau above; the last row
/// of `A` is `b`.
pub fn amplification(y: f64) -> f64 {
    // Complex numbers as (re, im); z = iy.
    let mut stages = [(1.0, 0.0); 7];
    for (i, row) in A.iter().enumerate() {
        let (re, im) = row.iter().zip(&stages).fold((0.0, 0.0), |(re, im), (a, s)| (re + a * s.0, im + a * s.1));
        // 1 + iy (re + i im) = (1 - y im) + i y re.
        stages[i + 1] = (1.0 - y * im, y * re);
    }
    let (re, im) = stages[6];
    re.hypot(im)
}

/// The largest `y = hω` at which `n = span ω / y` steps amplify an undamped mode of frequency
/// `ω` by at most `growth` over `span` seconds: `ln |R(iy)| · span ω / y ≤ ln growth`, and at
/// least [`IMAGINARY_STABILITY`], where no mode grows at all. `ln |R(iy)|/y` increases with `y`
/// above that, so bisection finds it.
pub fn bounded_growth(omega_span: f64, growth: f64) -> f64 {
    let within = |y: f64| amplification(y).ln() * omega_span / y <= growth.ln();
    let (mut lo, mut hi) = (IMAGINARY_STABILITY, 3.0);
    if within(hi) {
        return hi;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if within(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// `sum = Σ_s weights_s stages_s`, component by component, added in the order of the stages
/// from `+0`.
#[inline(always)]
fn weighted_sum(weights: &[f64], stages: &[Vec<f64>], sum: &mut [f64]) {
    let first = &stages[0][..sum.len()];
    for (x, k) in sum.iter_mut().zip(first) {
        *x = 0.0 + weights[0] * k;
    }
    for (w, stage) in weights.iter().zip(stages).skip(1) {
        for (x, k) in sum.iter_mut().zip(&stage[..]) {
            *x += w * k;
        }
    }
}

/// The first `S` weights and the first `S` stages cut to `len` components.
#[inline(always)]
fn columns<'a, const S: usize>(weights: &[f64], stages: &'a [Vec<f64>], len: usize) -> ([f64; S], [&'a [f64]; S]) {
    (std::array::from_fn(|s| weights[s]), std::array::from_fn(|s| &stages[s][..len]))
}

/// `Σ_s w_s k_s` at component `j`, added in the order of the stages from `+0` (as
/// [`weighted_sum`] adds them).
#[inline(always)]
fn stage_sum<const S: usize>(w: &[f64; S], k: &[&[f64]; S], j: usize) -> f64 {
    let mut sum = 0.0 + w[0] * k[0][j];
    for s in 1..S {
        sum += w[s] * k[s][j];
    }
    sum
}

/// `out = y + h Σ_s weights_s stages_s` over the first `S` stages: one pass over the
/// components, each sum kept in a register ([`stage_sum`]), compiled for the widest vectors
/// the processor has (`pulp`'s runtime dispatch, as [`crate::linalg::stencil`] does). Every
/// width gives the same sums to the bit: each component adds its terms in the same order,
/// and no multiply and add are fused.
fn advance<const S: usize>(stage: (&[f64], &[Vec<f64>], &[f64], f64), out: &mut [f64]) {
    pulp::Arch::new().dispatch(Advance::<S> { stage, out });
}

/// [`advance`] for `pulp`'s dispatch.
struct Advance<'a, const S: usize> {
    stage: (&'a [f64], &'a [Vec<f64>], &'a [f64], f64),
    out: &'a mut [f64],
}

impl<const S: usize> pulp::WithSimd for Advance<'_, S> {
    type Output = ();

    #[inline(always)]
    fn with_simd<V: pulp::Simd>(self, _: V) {
        let (weights, stages, y, h) = self.stage;
        let len = self.out.len();
        let (w, k) = columns::<S>(weights, stages, len);
        for (j, (out, y)) in self.out.iter_mut().zip(&y[..len]).enumerate() {
            *out = y + h * stage_sum(&w, &k, j);
        }
    }
}

/// The pair's error is per step and falls as `h⁵`: the next step is `0.9 h (tolerance/error)^{1/5}`,
/// at most 5 times the last.
pub(crate) const FIFTH_ORDER: ErrorScaling = ErrorScaling { per_unit_step: false, root: fifth_root, max_growth: 5.0 };

fn fifth_root(x: f64) -> f64 {
    x.powf(0.2)
}

/// Tsitouras' 5(4) pair on `ẏ = f(t, y)`: its stages and one step.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Tsit5 {
    stages: [Vec<f64>; 7],
    work: Vec<f64>,
    /// The weighted sum of the stages, per component (a buffer, not state).
    #[serde(skip)]
    sum: Vec<f64>,
}

impl Tsit5 {
    /// Workspace for systems of `len` unknowns.
    pub fn new(len: usize) -> Self {
        Self { stages: std::array::from_fn(|_| vec![0.0; len]), work: vec![0.0; len], sum: vec![0.0; len] }
    }

    /// Whether the workspace is for `len` unknowns.
    pub(super) fn fits(&self, len: usize) -> bool {
        self.work.len() == len && self.stages.iter().all(|stage| stage.len() == len)
    }

    /// One step of `h` from `y` at `t`, whose rate `f(t, y)` is `rate`; `f(t, y, ẏ)` fills
    /// `ẏ`. Returns the error estimate `max_j |(y₅ - y₄)_j| / (scale_j + max(|y_j|, |y₅_j|))`
    /// (infinite if anything is not finite); the fifth-order solution `y₅` and its rate are
    /// then [`Self::solution`] and [`Self::solution_rate`] (FSAL: the last stage is there).
    ///
    /// Each weighted sum `Σ_s a_s k_s` is accumulated stage after stage over all components at
    /// once (loops the compiler vectorizes), in the order of the stages.
    pub fn step(
        &mut self,
        y: &[f64],
        rate: &[f64],
        t: f64,
        h: f64,
        scale: &[f64],
        mut f: impl FnMut(f64, &[f64], &mut [f64]),
    ) -> f64 {
        let len = y.len();
        self.sum.resize(len, 0.0);
        self.stages[0].copy_from_slice(rate);
        for (i, row) in A.iter().enumerate() {
            let (known, next) = self.stages.split_at_mut(i + 1);
            let stage = (&row[..=i], &*known, y, h);
            match i {
                0 => advance::<1>(stage, &mut self.work),
                1 => advance::<2>(stage, &mut self.work),
                2 => advance::<3>(stage, &mut self.work),
                3 => advance::<4>(stage, &mut self.work),
                4 => advance::<5>(stage, &mut self.work),
                _ => advance::<6>(stage, &mut self.work),
            }
            // The last row is b: the last stage is evaluated at y₅ itself.
            f(t + C[i] * h, &self.work, &mut next[0]);
        }
        let (w, k) = columns::<7>(&ERROR, &self.stages, len);
        let mut error: f64 = 0.0;
        for j in 0..len {
            let e = stage_sum(&w, &k, j) * h;
            let size = scale[j] + y[j].abs().max(self.work[j].abs());
            error = error.max((e / size).abs());
        }
        // Every component checked, without an early exit, so that the check compiles to vector
        // instructions.
        let finite = self.work.iter().chain(&self.stages[6]).fold(true, |finite, x| finite & x.is_finite());
        if error.is_finite() && finite { error } else { f64::INFINITY }
    }

    /// Component `j` of the last [`Self::step`]'s dense output, `y_j + h Σ_i b_i(θ) k_ij`, for
    /// the step of `h` from `y_j` and the weights `b_i(θ)` of [`dense_weights`].
    pub fn dense_component(&self, j: usize, y_j: f64, h: f64, weights: &[f64; 7]) -> f64 {
        let sum = weights.iter().zip(&self.stages).fold(0.0, |sum, (w, k)| sum + w * k[j]);
        y_j + h * sum
    }

    /// The last [`Self::step`]'s dense output at the fraction `theta` of its step of `h` from `y`,
    /// into `out`: fourth-order accurate everywhere in the step, at no new evaluation of `f`.
    pub fn dense_output(&mut self, y: &[f64], h: f64, theta: f64, out: &mut Vec<f64>) {
        self.sum.resize(y.len(), 0.0);
        weighted_sum(&dense_weights(theta), &self.stages, &mut self.sum);
        out.clear();
        out.extend(y.iter().zip(&self.sum).map(|(y, sum)| y + h * sum));
    }

    /// The fifth-order solution of the last [`Self::step`].
    pub fn solution(&self) -> &[f64] {
        &self.work
    }

    /// Its rate `f(t + h, y₅)`.
    pub fn solution_rate(&self) -> &[f64] {
        &self.stages[6]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `y'' = -y` as `(y, y')`, whose solution from `(1, 0)` is `(cos t, -sin t)`.
    fn oscillator(_: f64, y: &[f64], rate: &mut [f64]) {
        rate[0] = y[1];
        rate[1] = -y[0];
    }

    /// Error at `t = 1` after `steps` equal steps against the closed form.
    fn global_error(steps: usize) -> f64 {
        let mut pair = Tsit5::new(2);
        let (mut y, mut rate, h) = (vec![1.0, 0.0], vec![0.0, -1.0], 1.0 / steps as f64);
        for k in 0..steps {
            pair.step(&y, &rate, k as f64 * h, h, &[1.0, 1.0], oscillator);
            y.copy_from_slice(pair.solution());
            rate.copy_from_slice(pair.solution_rate());
        }
        (y[0] - 1.0_f64.cos()).abs().max((y[1] + 1.0_f64.sin()).abs())
    }

    /// The stage sums compiled for 256-bit vectors, where this processor has them, are the
    /// scalar ones to the bit, for every stage and a length that is no multiple of the lanes.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_stage_sums_are_the_same_at_every_vector_width() {
        use pulp::WithSimd;
        let Some(v3) = pulp::x86::V3::try_new() else {
            eprintln!("SKIPPED: this processor has no AVX2, so only the scalar sums run");
            return;
        };
        let len = 103;
        // Values over 600 orders of magnitude and both signs, from a linear congruential sequence.
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            let unit = (state >> 11) as f64 / (1u64 << 53) as f64;
            (unit - 0.5) * 10f64.powi(((state >> 3) % 600) as i32 - 300)
        };
        let stages: Vec<Vec<f64>> = (0..7).map(|_| (0..len).map(|_| next()).collect()).collect();
        let y: Vec<f64> = (0..len).map(|_| next()).collect();
        for (i, row) in A.iter().enumerate() {
            let stage = (&row[..=i], &stages[..], &y[..], 0.0173);
            let (mut scalar, mut wide) = (vec![f64::NAN; len], vec![f64::NAN; len]);
            macro_rules! both {
                ($s:literal) => {{
                    Advance::<$s> { stage, out: &mut scalar }.with_simd(pulp::Scalar::new());
                    pulp::Simd::vectorize(v3, Advance::<$s> { stage, out: &mut wide });
                }};
            }
            match i {
                0 => both!(1),
                1 => both!(2),
                2 => both!(3),
                3 => both!(4),
                4 => both!(5),
                _ => both!(6),
            }
            for (j, (s, w)) in scalar.iter().zip(&wide).enumerate() {
                assert_eq!(s.to_bits(), w.to_bits(), "stage {} component {j}: {s} against {w}", i + 2);
            }
        }
    }

    #[test]
    fn one_step_on_an_oscillator_grows_it_by_the_stability_function() {
        // One step of h on y'' = -y (ω = 1) from (1, 0) multiplies the amplitude
        // √(y² + y'²) by |R(ih)|: stepping the tableau against the polynomial of `amplification`,
        // and both against an independent evaluation (NumPy, complex arithmetic on the same
        // coefficients): 0.9999999923791167 at 0.25, 1.0001280140643498 at 1, 1.0255397313319492
        // at 2, and a first crossing of 1 at 0.47797886884.
        for (h, expected) in
            [(0.25, 0.999_999_992_379_116_7), (1.0, 1.000_128_014_064_349_8), (2.0, 1.025_539_731_331_949_2)]
        {
            let mut pair = Tsit5::new(2);
            pair.step(&[1.0, 0.0], &[0.0, -1.0], 0.0, h, &[1.0, 1.0], oscillator);
            let stepped = pair.solution()[0].hypot(pair.solution()[1]);
            assert!((stepped - expected).abs() < 1e-14, "h = {h}: stepped {stepped}, expected {expected}");
            assert!((amplification(h) - expected).abs() < 1e-14, "h = {h}: {}", amplification(h));
        }
        assert!(amplification(IMAGINARY_STABILITY) <= 1.0 && amplification(0.4780) > 1.0);
        for k in 1..=477 {
            let y = k as f64 * 1e-3;
            assert!(amplification(y) <= 1.0, "|R({y}i)| = {}", amplification(y));
        }
    }

    #[test]
    fn the_bounded_growth_step_amplifies_by_the_growth_allowed() {
        // The paper case's highest frequency (≈ 45 rad/s) over 1000 s, doubling allowed.
        let omega_span = 45.0 * 1000.0;
        let y = bounded_growth(omega_span, 2.0);
        let growth = amplification(y).powf(omega_span / y);
        assert!((growth - 2.0).abs() < 1e-6, "y = {y}: growth {growth}");
        assert!((0.7..0.8).contains(&y), "y = {y}");
        // A run too long for any growth keeps within the imaginary-axis limit.
        let y = bounded_growth(1e30, 2.0);
        assert!((IMAGINARY_STABILITY..0.47798).contains(&y) && amplification(y) <= 1.0, "y = {y}");
    }

    #[test]
    fn the_dense_output_ends_on_the_solution_and_is_fourth_order_inside_the_step() {
        // At θ = 1 the weights are b, the last row of A (b₇ = 0): the dense output is y₅.
        let ends = dense_weights(1.0);
        for (i, w) in ends.iter().enumerate() {
            let b = if i < 6 { A[5][i] } else { 0.0 };
            assert!((w - b).abs() < 1e-13, "b_{i}(1) = {w}, b_{i} = {b}");
        }
        assert_eq!(dense_weights(0.0), [0.0; 7]);
        // Inside one step on y'' = -y from (1, 0), against the closed form (cos, -sin): the
        // error at θ = 0.4 falls as h⁵ (local error of a fourth-order interpolant).
        let error_at = |h: f64| {
            let mut pair = Tsit5::new(2);
            pair.step(&[1.0, 0.0], &[0.0, -1.0], 0.0, h, &[1.0, 1.0], oscillator);
            let mut out = Vec::new();
            pair.dense_output(&[1.0, 0.0], h, 0.4, &mut out);
            let t = 0.4 * h;
            let component = pair.dense_component(1, 0.0, h, &dense_weights(0.4));
            assert_eq!(component, out[1]);
            (out[0] - t.cos()).abs().max((out[1] + t.sin()).abs())
        };
        let orders: Vec<f64> = [0.4, 0.2, 0.1].iter().map(|&h| (error_at(h) / error_at(h / 2.0)).log2()).collect();
        for order in &orders {
            assert!((4.5..5.5).contains(order), "dense output's local error scales as h^{order}; all: {orders:?}");
        }
    }

    #[test]
    fn the_tableau_is_consistent() {
        for (i, row) in A.iter().enumerate() {
            let sum: f64 = row.iter().sum();
            assert!((sum - C[i]).abs() < 1e-14, "row {i}: Σ a = {sum}, c = {}", C[i]);
        }
        let weights: f64 = A[5].iter().sum();
        assert!((weights - 1.0).abs() < 1e-14, "Σ b = {weights}");
        let error: f64 = ERROR.iter().sum();
        assert!(error.abs() < 1e-14, "Σ (b - b̂) = {error}");
    }

    #[test]
    fn the_solution_converges_at_fifth_order() {
        // Against the closed form: halving the step divides the error by 2⁵.
        let errors: Vec<f64> = [8, 16, 32, 64].iter().map(|&n| global_error(n)).collect();
        for pair in errors.windows(2) {
            let order = (pair[0] / pair[1]).log2();
            assert!((4.7..5.5).contains(&order), "observed order {order} from errors {errors:?}");
        }
    }

    #[test]
    fn the_error_estimate_is_that_of_the_fourth_order_solution() {
        // The estimate of one step is y₅ - y₄ ≈ the local error of y₄, C h⁵.
        let estimate = |h: f64| {
            let mut pair = Tsit5::new(2);
            pair.step(&[1.0, 0.0], &[0.0, -1.0], 0.0, h, &[1.0, 1.0], oscillator)
        };
        let ratios: Vec<f64> = [0.4, 0.2, 0.1].iter().map(|&h| (estimate(h) / estimate(h / 2.0)).log2()).collect();
        for order in &ratios {
            assert!((4.5..5.5).contains(order), "estimate scales as h^{order}; all: {ratios:?}");
        }
        let mut pair = Tsit5::new(2);
        let estimate = pair.step(&[1.0, 0.0], &[0.0, -1.0], 0.0, 0.1, &[1.0, 1.0], oscillator);
        let y5 = pair.solution();
        let true_error = (y5[0] - 0.1_f64.cos()).abs().max((y5[1] + 0.1_f64.sin()).abs());
        // y₅'s own error is much smaller than the estimate (which measures y₄'s).
        assert!(true_error < estimate, "y5 error {true_error:e}, estimate {estimate:e}");
    }
}
