//! Prescribed motion: a velocity history in phases, every change smoothed over a ramp.
//!
//! The main body of a contact (§3.2's moving base) and a boundary with
//! a prescribed velocity (eq. 10's `S_v`) move this way. A history starts from rest; each phase
//! holds a velocity for a duration, and each change of velocity, the first from rest included,
//! is spread over `ramp` seconds by the polynomial `s³ (10 - 15 s + 6 s²)`, `s = τ/ramp`, whose
//! first and second derivatives vanish at both ends: acceleration and jerk stay continuous, so
//! a start, a stop or a reversal excites the stiff contact modes as little as a polynomial
//! ramp can. The ramps superpose, so phases shorter than the ramp are allowed.

use serde::{Deserialize, Serialize};

/// A velocity history (m/s) of two components, from rest at `t = 0`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Motion {
    /// `(start, change of velocity)` of every phase, in time order.
    changes: Vec<(f64, [f64; 2])>,
    /// Time over which each change is spread (s); 0 makes every change a jump.
    ramp: f64,
}

impl Motion {
    /// Never moves.
    pub fn at_rest() -> Self {
        Self { changes: Vec::new(), ramp: 0.0 }
    }

    /// Reaches `velocity` from rest over `ramp` from `t = 0`, then keeps it.
    pub fn constant(velocity: [f64; 2], ramp: f64) -> Self {
        Self { changes: vec![(0.0, velocity)], ramp }
    }

    /// Holds each `(velocity, duration)` in turn, from `t = 0`; a phase without a duration lasts
    /// for ever, and after the last finite one the motion stops (velocity 0).
    pub fn phases(phases: &[([f64; 2], Option<f64>)], ramp: f64) -> Self {
        let mut changes = Vec::with_capacity(phases.len() + 1);
        let (mut start, mut previous) = (0.0, [0.0, 0.0]);
        for &(velocity, duration) in phases {
            changes.push((start, [velocity[0] - previous[0], velocity[1] - previous[1]]));
            previous = velocity;
            match duration {
                Some(d) => start += d,
                None => return Self { changes, ramp },
            }
        }
        changes.push((start, [-previous[0], -previous[1]]));
        Self { changes, ramp }
    }

    /// Velocity at `t` (m/s).
    pub fn velocity_at(&self, t: f64) -> [f64; 2] {
        self.sum(t, |change, tau| {
            if tau >= self.ramp {
                change
            } else {
                let s = tau / self.ramp;
                change.map(|c| c * s * s * s * (10.0 - 15.0 * s + 6.0 * s * s))
            }
        })
    }

    /// Displacement at `t` (m), the integral of [`Self::velocity_at`] from 0.
    pub fn displacement_at(&self, t: f64) -> [f64; 2] {
        self.sum(t, |change, tau| {
            let ramp = self.ramp;
            if tau >= ramp {
                change.map(|c| c * (tau - 0.5 * ramp))
            } else {
                let s = tau / ramp;
                change.map(|c| c * ramp * s * s * s * s * (2.5 - 3.0 * s + s * s))
            }
        })
    }

    /// The largest speed the history reaches (m/s), the sum of the changes' sizes at most.
    pub fn largest_speed(&self) -> f64 {
        let mut velocity = [0.0, 0.0];
        let mut largest: f64 = 0.0;
        for (_, change) in &self.changes {
            velocity = [velocity[0] + change[0], velocity[1] + change[1]];
            largest = largest.max(velocity[0].hypot(velocity[1]));
        }
        largest
    }

    /// The first nonzero velocity, the direction the motion starts in; `None` at rest.
    pub fn first_velocity(&self) -> Option<[f64; 2]> {
        self.changes.first().map(|(_, change)| *change).filter(|v| v[0] != 0.0 || v[1] != 0.0)
    }

    /// Whether the motion never moves.
    pub fn is_at_rest(&self) -> bool {
        self.changes.iter().all(|(_, c)| c[0] == 0.0 && c[1] == 0.0)
    }

    /// `Σ term(change, t - start)` over the changes that have started by `t`. The first term is
    /// taken as it is, not added to zero, so a single change keeps its exact value and sign.
    fn sum(&self, t: f64, term: impl Fn([f64; 2], f64) -> [f64; 2]) -> [f64; 2] {
        self.changes
            .iter()
            .filter(|(start, _)| t >= *start)
            .map(|&(start, change)| term(change, t - start))
            .reduce(|a, b| [a[0] + b[0], a[1] + b[1]])
            .unwrap_or([0.0, 0.0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ramp's velocity integrates to its displacement (Simpson's rule, fine steps), and
    /// a phase history reverses and stops as asked.
    #[test]
    fn displacement_is_the_integral_of_velocity() {
        let motion =
            Motion::phases(&[([1.0, 0.5], Some(30.0)), ([0.0, 0.0], Some(20.0)), ([-2.0, 1.0], Some(25.0))], 7.0);
        let (n, t_end) = (20_000, 100.0);
        let h = t_end / n as f64;
        let mut integral = [0.0, 0.0];
        for k in 0..n {
            let (a, m, b) = (k as f64 * h, (k as f64 + 0.5) * h, (k + 1) as f64 * h);
            let (va, vm, vb) = (motion.velocity_at(a), motion.velocity_at(m), motion.velocity_at(b));
            for c in 0..2 {
                integral[c] += h / 6.0 * (va[c] + 4.0 * vm[c] + vb[c]);
            }
        }
        let exact = motion.displacement_at(t_end);
        for c in 0..2 {
            assert!((integral[c] - exact[c]).abs() < 1e-9, "component {c}: {} against {}", integral[c], exact[c]);
        }
        // Hand values: full speed in the first phase after the ramp, at rest in the second,
        // the third's velocity at its end, and rest after the last phase.
        assert_eq!(motion.velocity_at(20.0), [1.0, 0.5]);
        assert_eq!(motion.velocity_at(45.0), [0.0, 0.0]);
        assert_eq!(motion.velocity_at(65.0), [-2.0, 1.0]);
        assert_eq!(motion.velocity_at(90.0), [0.0, 0.0]);
        // After a 7 s ramp the displacement lags a jump by half the ramp: 1 m/s × (30 - 3.5) s.
        assert!((motion.displacement_at(30.0)[0] - 26.5).abs() < 1e-12);
        assert_eq!(motion.largest_speed(), 5.0_f64.sqrt());
    }

    /// A constant motion is the block's ramp to the bit: `v s³(10 - 15 s + 6 s²)`.
    #[test]
    fn a_constant_motion_is_the_start_up_ramp() {
        let (v, ramp) = (1.0e-3, 10.0);
        let motion = Motion::constant([v, 0.0], ramp);
        for t in [0.0, 0.37, 5.0, 9.99, 10.0, 123.4] {
            let s: f64 = t / ramp;
            let expected = if t >= ramp { v } else { v * s * s * s * (10.0 - 15.0 * s + 6.0 * s * s) };
            assert_eq!(motion.velocity_at(t)[0].to_bits(), expected.to_bits(), "t = {t}");
        }
        assert_eq!(Motion::constant([-1.0, 0.0], 2.0).velocity_at(0.0)[0].to_bits(), (-0.0_f64).to_bits());
        assert!(Motion::at_rest().is_at_rest());
        assert_eq!(Motion::at_rest().velocity_at(3.0), [0.0, 0.0]);
    }
}
