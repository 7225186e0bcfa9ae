//! slipfront's logarithm of `R` (`friction::ln`) against the system's `log`, bit for bit.
//!
//! The module follows the algorithm, table and fused multiply-adds of the `log` of glibc 2.28
//! and later as built for processors with FMA, so on x86-64 Linux with glibc each lane, in four
//! lanes of AVX2 or one at a time, must be `f64::ln` to the bit: the friction law then gives
//! the same rates, and every run the same results, as when it called `log` point by point.
//! Elsewhere (another C library) `f64::ln` is another function, and these tests do not apply.
#![cfg(all(target_arch = "x86_64", target_os = "linux", target_env = "gnu"))]

use slipfront::friction::ln::{ln, ln_lanes};

/// Whether glibc's `log` here is its FMA build (the one the module follows) and the module
/// takes its four-lane path.
fn fma_machine() -> bool {
    std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
}

/// xorshift64: a fixed, reproducible stream of bits.
fn next(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// Asserts that four lanes at once, five (four and one left over), and one value at a time
/// all give `f64::ln`'s bits for every value of `xs`.
fn assert_same_as_system_log(xs: &[f64]) {
    assert!(fma_machine(), "this machine's log is not glibc's FMA build: the comparison does not apply");
    for chunk in xs.chunks_exact(5) {
        let expected: Vec<u64> = chunk.iter().map(|x| x.ln().to_bits()).collect();
        let four = ln_lanes([chunk[0], chunk[1], chunk[2], chunk[3]]);
        let five = ln_lanes([chunk[0], chunk[1], chunk[2], chunk[3], chunk[4]]);
        for l in 0..5 {
            let (x, want) = (chunk[l], expected[l]);
            let same = |got: f64| got.to_bits() == want || (got.is_nan() && f64::from_bits(want).is_nan());
            assert!(same(five[l]), "ln({x:e}) in five lanes: {:e}, log gives {:e}", five[l], f64::from_bits(want));
            assert!(same(ln(x)), "ln({x:e}) alone: {:e}, log gives {:e}", ln(x), f64::from_bits(want));
            if l < 4 {
                assert!(same(four[l]), "ln({x:e}) in four lanes: {:e}, log gives {:e}", four[l], f64::from_bits(want));
            }
        }
    }
}

#[test]
fn every_kind_of_double_is_the_system_log_to_the_bit() {
    let mut state = 0x9e37_79b9_7f4a_7c15;
    // Any non-negative double (bit patterns: subnormals, normals, infinity, NaNs).
    let any: Vec<f64> = (0..1_000_000).map(|_| f64::from_bits(next(&mut state) >> 1)).collect();
    assert_same_as_system_log(&any);
    // Negative numbers.
    let negative: Vec<f64> = (0..50_000).map(|_| -f64::from_bits(next(&mut state) >> 1)).collect();
    assert_same_as_system_log(&negative);
}

#[test]
fn the_range_of_r_is_the_system_log_to_the_bit() {
    let mut state = 0x2545_f491_4f6c_dd1d;
    let unit = |s: &mut u64| (next(s) >> 11) as f64 / (1u64 << 53) as f64;
    // `R` in (0, 1], uniform; then within 1/16 of 1, where the near polynomial takes over,
    // uniform in bits; then the last 2^-20 below 1, where a point on its loading branch sits.
    let uniform: Vec<f64> = (0..1_000_000).map(|_| unit(&mut state)).collect();
    let near: Vec<f64> = (0..1_000_000)
        .map(|_| f64::from_bits(0x3fee_0000_0000_0000 + next(&mut state) % 0x0004_0000_0000_0000))
        .collect();
    let close: Vec<f64> = (0..1_000_000).map(|_| 1.0 - unit(&mut state) * 2f64.powi(-20)).collect();
    assert_same_as_system_log(&uniform);
    assert_same_as_system_log(&near);
    assert_same_as_system_log(&close);
}

#[test]
fn the_edges_are_the_system_log_to_the_bit() {
    let around = |x: f64| [f64::from_bits(x.to_bits() - 1), x, f64::from_bits(x.to_bits() + 1)];
    let mut xs: Vec<f64> = [
        1.0,
        1.0 - 1.0 / 16.0,
        f64::from_bits(0x3ff1_0900_0000_0000),
        f64::MIN_POSITIVE,
        f64::MAX,
        0.5,
        2.0,
        f64::from_bits(0x3fe6_0000_0000_0000),
        f64::from_bits(0x3ff6_0000_0000_0000),
    ]
    .into_iter()
    .flat_map(around)
    .collect();
    xs.extend([0.0, -0.0, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, -1.0, 5e-324, 1e-310, f64::EPSILON]);
    while !xs.len().is_multiple_of(5) {
        xs.push(1.0);
    }
    assert_same_as_system_log(&xs);
    assert_eq!(ln(1.0).to_bits(), 0, "ln 1 is +0");
    assert_eq!(ln(0.0), f64::NEG_INFINITY);
    assert!(ln(-1.0).is_nan() && ln(f64::NAN).is_nan());
}
