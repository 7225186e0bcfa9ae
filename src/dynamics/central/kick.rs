//! The row loops of a central-difference kick, after the product `K u` of a chunk of rows.
//!
//! With `a = M⁻¹ (f⁰ + f_c - f_c(0) - K u)` row by row, a step's last kick is `v += ½h a`
//! (keeping `a`), and the kick between two sub-steps is the second half kick of one and the
//! first of the next with its drift, `v_{n+3/2} = v_{n+½} + h a_{n+1}`,
//! `u_{n+2} = u_{n+1} + h v_{n+3/2}`, written to a second displacement so that the products
//! of the other chunks still read `u_{n+1}`. The loops index slices of equal length, so that
//! they compile to vector instructions.

use crate::linalg::stencil::TemplateMatrix;

/// Which kick a chunk of rows takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kick {
    /// `v += ½h a`, `a` kept: the end of a step.
    Half,
    /// `v += h a`, `u_next = u + h v` and its swapped copy: between two sub-steps.
    WholeAndDrift,
}

/// What every chunk reads, indexed by row.
pub struct Forces<'a> {
    /// `f_c - f_c(0)`.
    pub contact_force: &'a [f64],
    pub inverse_mass: &'a [f64],
    /// `f⁰(t)` as a pattern and its factor, if the body is loaded.
    pub load: Option<(&'a [f64], f64)>,
    /// `u` before the kick.
    pub displacement: &'a [f64],
}

/// One chunk's rows `first..first + stiffness_force.len()`, written by the kick.
pub struct Rows<'a> {
    pub first: usize,
    pub acceleration: &'a mut [f64],
    pub velocity: &'a mut [f64],
    /// `K u` of the rows.
    pub stiffness_force: &'a mut [f64],
    pub next_displacement: &'a mut [f64],
    pub next_swapped: &'a mut [f64],
}

impl Rows<'_> {
    /// The kick `kick` of these rows with step `h`, given their `K u` in `stiffness_force`.
    /// After [`Kick::Half`], whether every displacement and velocity of the rows is finite
    /// (`true` after the other kick, which is not the end of a step).
    #[inline]
    pub fn kick(self, kick: Kick, h: f64, forces: &Forces) -> bool {
        let rows = self.first..self.first + self.stiffness_force.len();
        match forces.load {
            Some((pattern, g)) => {
                let pattern = &pattern[rows];
                self.kick_with(kick, h, forces, |i| pattern[i] * g)
            }
            None => self.kick_with(kick, h, forces, |_| 0.0),
        }
    }

    /// [`Rows::kick`] with `f⁰` of row `first + i` given by `load(i)`.
    #[inline(always)]
    fn kick_with(self, kick: Kick, h: f64, forces: &Forces, load: impl Fn(usize) -> f64) -> bool {
        let len = self.stiffness_force.len();
        let rows = self.first..self.first + len;
        let (fc, inverse_mass, u) =
            (&forces.contact_force[rows.clone()], &forces.inverse_mass[rows.clone()], &forces.displacement[rows]);
        let (v, ku) = (&mut self.velocity[..len], &self.stiffness_force[..len]);
        match kick {
            Kick::Half => {
                let a = &mut self.acceleration[..len];
                let mut finite = true;
                for i in 0..len {
                    a[i] = (load(i) + fc[i] - ku[i]) * inverse_mass[i];
                    v[i] += 0.5 * h * a[i];
                    finite &= v[i].is_finite() & u[i].is_finite();
                }
                finite
            }
            Kick::WholeAndDrift => {
                let u_next = &mut self.next_displacement[..len];
                for i in 0..len {
                    v[i] += h * ((load(i) + fc[i] - ku[i]) * inverse_mass[i]);
                    u_next[i] = u[i] + h * v[i];
                }
                TemplateMatrix::swap_pairs(u_next, &mut self.next_swapped[..len]);
                true
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What four rows hold after `kick` from velocities `v0` with `K u` = `ku`: `(a, v,
    /// u_next, swapped, finite)`.
    type Kicked = ([f64; 4], [f64; 4], [f64; 4], [f64; 4], bool);

    fn kicked(kick: Kick, h: f64, forces: &Forces, v0: [f64; 4], ku: [f64; 4]) -> Kicked {
        let (mut a, mut v, mut k, mut u_next, mut swapped) = ([0.0; 4], v0, ku, [0.0; 4], [0.0; 4]);
        let rows = Rows {
            first: 0,
            acceleration: &mut a,
            velocity: &mut v,
            stiffness_force: &mut k,
            next_displacement: &mut u_next,
            next_swapped: &mut swapped,
        };
        let finite = rows.kick(kick, h, forces);
        (a, v, u_next, swapped, finite)
    }

    /// Both kicks on four rows, with and without a load, against the formulas written out.
    #[test]
    fn kicks_follow_their_formulas() {
        let (h, g) = (0.5, 3.0);
        let ku = [1.0, -2.0, 0.25, 4.0];
        let (fc, inverse_mass, pattern) = ([0.0, 1.5, 0.0, -1.0], [0.5, 0.25, 2.0, 1.0], [1.0, 0.0, -1.0, 2.0]);
        let (u, v0) = ([0.1, 0.2, 0.3, 0.4], [1.0, 2.0, 3.0, 4.0]);
        for load in [None, Some((&pattern[..], g))] {
            let f = |i: usize| load.map_or(0.0, |(p, g)| p[i] * g);
            let a_of = |i: usize| (f(i) + fc[i] - ku[i]) * inverse_mass[i];
            let forces = Forces { contact_force: &fc, inverse_mass: &inverse_mass, load, displacement: &u };
            for kick in [Kick::Half, Kick::WholeAndDrift] {
                let (a, v, u_next, swapped, finite) = kicked(kick, h, &forces, v0, ku);
                assert!(finite);
                for i in 0..4 {
                    match kick {
                        Kick::Half => {
                            assert_eq!(a[i], a_of(i));
                            assert_eq!(v[i], v0[i] + 0.5 * h * a_of(i));
                        }
                        Kick::WholeAndDrift => {
                            assert_eq!(v[i], v0[i] + h * a_of(i));
                            assert_eq!(u_next[i], u[i] + h * v[i]);
                            assert_eq!(swapped[i], u_next[i ^ 1]);
                        }
                    }
                }
            }
        }
        let forces =
            Forces { contact_force: &fc, inverse_mass: &inverse_mass, load: None, displacement: &[f64::NAN; 4] };
        let (.., finite) = kicked(Kick::Half, h, &forces, v0, ku);
        assert!(!finite, "a displacement that is not finite is reported");
    }
}
