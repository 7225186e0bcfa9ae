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

/// The pair's error is per step and falls as `h⁵`: the next step is `0.9 h (tolerance/error)^{1/5}`,
/// at most 5 times the last.
pub(crate) const FIFTH_ORDER: ErrorScaling = ErrorScaling { per_unit_step: false, root: fifth_root, max_growth: 5.0 };

fn fifth_root(x: f64) -> f64 {
    x.powf(0.2)
}

/// Tsitouras' 5(4) pair on `ẏ = f(t, y)`: its stages and one step.
#[derive(Debug, Clone)]
pub struct Tsit5 {
    stages: [Vec<f64>; 7],
    work: Vec<f64>,
}

impl Tsit5 {
    /// Workspace for systems of `len` unknowns.
    pub fn new(len: usize) -> Self {
        Self { stages: std::array::from_fn(|_| vec![0.0; len]), work: vec![0.0; len] }
    }

    /// One step of `h` from `y` at `t`, whose rate `f(t, y)` is `rate`; `f(t, y, ẏ)` fills
    /// `ẏ`. Returns the error estimate `max_j |(y₅ - y₄)_j| / (scale_j + max(|y_j|, |y₅_j|))`
    /// (infinite if anything is not finite); the fifth-order solution `y₅` and its rate are
    /// then [`Self::solution`] and [`Self::solution_rate`] (FSAL: the last stage is there).
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
        self.stages[0].copy_from_slice(rate);
        for (i, row) in A.iter().enumerate() {
            for j in 0..len {
                let mut sum = 0.0;
                for (a, k) in row.iter().zip(&self.stages).take(i + 1) {
                    sum += a * k[j];
                }
                self.work[j] = y[j] + h * sum;
            }
            // The last row is b: the last stage is evaluated at y₅ itself.
            f(t + C[i] * h, &self.work, &mut self.stages[i + 1]);
        }
        let mut error: f64 = 0.0;
        for j in 0..len {
            let e: f64 = ERROR.iter().zip(&self.stages).map(|(w, k)| w * k[j]).sum::<f64>() * h;
            let size = scale[j] + y[j].abs().max(self.work[j].abs());
            error = error.max((e / size).abs());
        }
        if error.is_finite() && self.work.iter().chain(&self.stages[6]).all(|x| x.is_finite()) {
            error
        } else {
            f64::INFINITY
        }
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
