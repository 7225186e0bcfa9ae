//! The energy balance of a run: work put in by the base and the load against what is stored
//! (kinetic, strain, contact springs) and dissipated by friction; the rest is what the
//! integrator itself created or dissipated.

use crate::dynamics::body::LinearBody;
use crate::dynamics::contact::ContactBoundary;
use crate::dynamics::state::State;

/// Running energy balance (J per unit thickness, or J/m² per unit area).
///
/// `initial + work_base + work_load = kinetic + strain + contact_elastic + dissipation + numerical`,
/// where `initial` is what was stored when tracking began and `numerical` is what the
/// integrator itself dissipates (or adds).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EnergyLedger {
    /// `∫ Σ w f_t v_base dt`: work the moving base does through the contact.
    pub work_base: f64,
    /// `∫ f⁰(t)·v dt`: work of the external load beyond the initial equilibrium.
    pub work_load: f64,
    /// `½ vᵀ M v`.
    pub kinetic: f64,
    /// `½ uᵀ K u + uᵀ f_c(0)` (the second term is the work against the initial traction).
    pub strain: f64,
    /// `Σ w (f_t² - f_t(0)²) / (2 α_t)`: energy stored in the contact's elastic springs; where
    /// a contact's normal evolves, with the potential of its normal force beyond `K`'s springs
    /// ([`ContactBoundary::normal_potential`]), so that an open point's spring holds none.
    pub contact_elastic: f64,
    /// `∫ Σ w Λ |f_t| dt`: frictional dissipation.
    pub dissipation: f64,
    /// Kinetic + strain + contact-elastic energy when tracking began (0 from the initial
    /// equilibrium at rest).
    pub initial: f64,
}

impl EnergyLedger {
    /// The integrator's own dissipation: input minus everything accounted for.
    pub fn numerical(&self) -> f64 {
        self.initial + self.work_base + self.work_load
            - (self.kinetic + self.strain + self.contact_elastic + self.dissipation)
    }
}

impl EnergyLedger {
    /// Adds the work of the base and the load and the frictional dissipation over the step of
    /// `dt` from `old` to `new`.
    pub(crate) fn add_step(&mut self, body: &LinearBody, contact: &ContactBoundary, old: &State, new: &State, dt: f64) {
        let power_base = |state: &State| -> f64 {
            let bases = contact.base_velocities(state.time);
            contact
                .points
                .iter()
                .zip(&state.contact)
                .enumerate()
                .map(|(k, (p, c))| p.weight * c.traction_t * contact.base_along(k, &bases))
                .sum()
        };
        let power_load = |state: &State| -> f64 {
            let load = body.load_at(state.time);
            state.velocity.iter().enumerate().map(|(i, v)| load.at(i) * v).sum()
        };
        self.work_base += 0.5 * dt * (power_base(old) + power_base(new));
        // A load linear in time (the spring block's) with the velocity quadratic over the step
        // (linear acceleration): Simpson's rule integrates the load's power exactly.
        let load_mid = body.load_at(old.time + 0.5 * dt);
        let power_load_mid: f64 = old
            .velocity
            .iter()
            .zip(&old.acceleration)
            .zip(&new.acceleration)
            .enumerate()
            .map(|(i, ((v, a0), a1))| load_mid.at(i) * (v + 0.5 * dt * a0 + 0.125 * dt * (a1 - a0)))
            .sum();
        self.work_load += dt / 6.0 * (power_load(old) + 4.0 * power_load_mid + power_load(new));
        self.dissipation += contact
            .points
            .iter()
            .enumerate()
            .map(|(k, p)| {
                p.weight
                    * new.plastic_increment[k]
                    * 0.5
                    * (old.contact[k].traction_t.abs() + new.contact[k].traction_t.abs())
            })
            .sum::<f64>();
    }

    /// Sets the stored energies (kinetic, strain, contact springs) of `state`, measured from the
    /// initial equilibrium's tractions `initial_traction` and forces `initial_contact_force`.
    pub(crate) fn refresh(
        &mut self,
        body: &LinearBody,
        contact: &ContactBoundary,
        state: &State,
        initial_traction: &[f64],
        initial_contact_force: &[f64],
    ) {
        let s = state;
        self.kinetic = body.kinetic_energy(&s.velocity);
        self.strain = body.strain_energy(&s.displacement)
            + s.displacement.iter().zip(initial_contact_force).map(|(u, f)| u * f).sum::<f64>();
        self.contact_elastic = contact
            .points
            .iter()
            .zip(&s.contact)
            .zip(initial_traction)
            .enumerate()
            .map(|(k, ((p, c), f0))| {
                p.weight * (c.traction_t * c.traction_t - f0 * f0) / (2.0 * contact.params(k).alpha_t)
            })
            .sum();
        if contact.any_evolving() {
            self.contact_elastic +=
                (0..contact.points.len()).map(|k| contact.normal_potential(k, &s.displacement)).sum::<f64>();
        }
    }
}
