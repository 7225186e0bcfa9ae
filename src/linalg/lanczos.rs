//! The largest eigenvalue of a symmetric operator by Lanczos' iteration (Golub & Van Loan,
//! *Matrix Computations*, 4th ed., Alg. 10.1.1, without reorthogonalization, which leaves the
//! extreme Ritz value intact): the largest Ritz value approaches it from below.

/// The largest Ritz value of the symmetric operator `apply` (`y = A x`) on vectors of `n`
/// after at most `steps` steps, from a start with a component along every eigenvector (an
/// irrational sequence of both signs).
pub fn largest_eigenvalue(n: usize, steps: usize, mut apply: impl FnMut(&[f64], &mut [f64])) -> f64 {
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
    let mut q: Vec<f64> = (0..n).map(|i| ((i as f64 + 1.0) * 0.618_033_988_749_894_9).fract() - 0.5).collect();
    let norm = dot(&q, &q).sqrt();
    q.iter_mut().for_each(|v| *v /= norm);
    let mut previous = vec![0.0; n];
    let mut w = vec![0.0; n];
    let (mut alphas, mut betas) = (Vec::new(), Vec::new());
    let mut beta = 0.0;
    for _ in 0..steps.min(n) {
        apply(&q, &mut w);
        w.iter_mut().zip(&previous).for_each(|(w, p)| *w -= beta * p);
        let alpha = dot(&w, &q);
        w.iter_mut().zip(&q).for_each(|(w, q)| *w -= alpha * q);
        alphas.push(alpha);
        beta = dot(&w, &w).sqrt();
        if beta <= 1e-14 * alpha.abs() {
            break;
        }
        betas.push(beta);
        std::mem::swap(&mut previous, &mut q);
        q.iter_mut().zip(&w).for_each(|(q, w)| *q = w / beta);
    }
    let k = alphas.len();
    let tridiagonal = nalgebra::DMatrix::from_fn(k, k, |i, j| match i.abs_diff(j) {
        0 => alphas[i],
        1 => betas[i.min(j)],
        _ => 0.0,
    });
    tridiagonal.symmetric_eigenvalues().iter().copied().fold(0.0, f64::max)
}
