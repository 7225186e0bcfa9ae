//! The dynamic system of the paper's §2.2: a linear elastic body `M a + K u = f⁰ + f_c` whose
//! contact forces `f_c` follow the friction law, with what every time integrator shares.

use crate::dynamics::body::LinearBody;
use crate::dynamics::contact::ContactBoundary;
use crate::dynamics::energy::EnergyLedger;
use crate::dynamics::error::StepError;
use crate::dynamics::newton::max_abs;
use crate::dynamics::operator::Operator;
use crate::dynamics::settings::Settings;
use crate::dynamics::state::State;
use crate::friction::ContactState;

/// The assembled model: the linear body, its frictional contact, the current [`State`], and
/// what the methods share (Newton's operator, the energy ledger, the count of split steps).
/// The integrators ([`super::integrator`]) advance it; each keeps its own memory.
pub struct System {
    pub body: LinearBody,
    pub contact: ContactBoundary,
    pub settings: Settings,
    pub state: State,
    /// Each contact point's tangential traction in the initial equilibrium (Pa).
    initial_traction: Vec<f64>,
    /// `f_c(0)`: the contact forces of the initial equilibrium.
    pub(crate) initial_contact_force: Vec<f64>,
    /// Newton's operator `c₀ M + K + K_c`, built at its first use (Tsitouras' pair and
    /// central differences never need it).
    operator: Option<Operator>,
    ledger: Option<EnergyLedger>,
    /// The scale the energy check uses before much work has been done: the larger of
    /// [`strength_energy`] and [`drive_energy`].
    energy_scale: f64,
    split_steps: u64,
}

/// Everything of a [`System`] that a checkpoint keeps ([`System::memory`]): the state, the
/// energy ledger, the count of split steps, and what Newton's operator was last factored at
/// (the implicit Runge–Kutta stages reuse that factorization until they ask for another).
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct SystemMemory {
    pub state: State,
    ledger: Option<EnergyLedger>,
    split_steps: u64,
    factored: Option<(f64, Vec<f64>)>,
}

/// A saved state of [`System`] (see [`System::snapshot`]).
#[derive(Clone)]
pub(crate) struct Snapshot {
    pub(crate) state: State,
    ledger: Option<EnergyLedger>,
}

impl System {
    /// Sets up the system at rest in its initial equilibrium.
    pub fn new(body: LinearBody, contact: ContactBoundary, settings: Settings) -> Result<Self, StepError> {
        let n = body.dofs();
        let states: Vec<ContactState> = (0..contact.points.len())
            .map(|k| {
                ContactState::initial(contact.params(k), contact.traction_n[k], contact.points[k].loading_direction)
            })
            .collect();
        let initial_traction: Vec<f64> = states.iter().map(|s| s.traction_t).collect();
        let mut initial_contact_force = vec![0.0; n];
        for (point, s) in contact.points.iter().zip(&states) {
            point.scatter(point.weight * s.traction_t, &mut initial_contact_force);
        }
        let n_points = contact.points.len();
        let energy_scale = strength_energy(&contact).max(drive_energy(&body, settings.velocity_scale));
        let mut system = Self {
            state: State {
                time: 0.0,
                step: 0,
                displacement: vec![0.0; n],
                velocity: vec![0.0; n],
                acceleration: vec![0.0; n],
                contact: states,
                plastic_increment: vec![0.0; n_points],
                plastic_rate: Vec::new(),
            },
            body,
            contact,
            settings,
            initial_traction,
            initial_contact_force,
            operator: None,
            ledger: None,
            energy_scale,
            split_steps: 0,
        };
        if system.settings.energy_tolerance.is_some() {
            system.track_energy();
        }
        Ok(system)
    }

    /// Starts each contact point from the tangential traction `traction_t[k]` (Pa) rather than
    /// from `f0` alone: the body at rest in an equilibrium found before the run (a static solve
    /// under gravity, `crate::fem::equilibrium`) that these tractions hold. The contact forces
    /// `f_c(0)` that eq. (14)'s displacements are measured from, and the energy ledger's zero,
    /// follow. Call before the first step.
    pub fn start_from_tractions(&mut self, traction_t: &[f64]) {
        for (state, &f_t) in self.state.contact.iter_mut().zip(traction_t) {
            state.traction_t = f_t;
        }
        self.initial_traction = self.state.contact.iter().map(|s| s.traction_t).collect();
        self.initial_contact_force = vec![0.0; self.body.dofs()];
        for (point, s) in self.contact.points.iter().zip(&self.state.contact) {
            point.scatter(point.weight * s.traction_t, &mut self.initial_contact_force);
        }
        if self.ledger.is_some() {
            self.track_energy();
        }
    }

    /// Advances by `dt` as two steps of `dt/2` taken by `half_step`, reported as one step: the
    /// step counter moves by one and `plastic_increment` holds the slip of both halves.
    pub(crate) fn two_halves(
        &mut self,
        dt: f64,
        mut half_step: impl FnMut(&mut Self, f64) -> Result<(), StepError>,
    ) -> Result<(), StepError> {
        half_step(self, 0.5 * dt)?;
        let first = self.state.plastic_increment.clone();
        half_step(self, 0.5 * dt)?;
        for (p, f) in self.state.plastic_increment.iter_mut().zip(first) {
            *p += f;
        }
        self.state.step -= 1;
        Ok(())
    }

    /// Everything a step changes, to undo a trial step.
    pub(crate) fn snapshot(&self) -> Snapshot {
        Snapshot { state: self.state.clone(), ledger: self.ledger }
    }

    /// Returns to `snapshot`.
    pub(crate) fn restore(&mut self, snapshot: Snapshot) {
        self.state = snapshot.state;
        self.ledger = snapshot.ledger;
    }

    /// Assembles and factors `c₀ M + K + K_c` unless the factored one is the same: Newton's
    /// operator of Wilson's step (`c₀ = 6/τ²`) and of the implicit Runge–Kutta stages
    /// ([`crate::dynamics::rate_form::sdirk4`], `c₀ = 1/(hγ)²`). `contact_stiffness` holds each point's `-w ∂f_t/∂ū`.
    pub(crate) fn factor_operator(&mut self, c0: f64, contact_stiffness: &[f64]) -> Result<(), StepError> {
        let operator = match self.operator.as_mut() {
            Some(operator) => operator,
            None => self.operator.insert(Operator::new(&self.body, &self.contact).map_err(StepError::Factor)?),
        };
        operator.factor(&self.body, &self.contact, c0, contact_stiffness).map_err(StepError::Factor)
    }

    /// Solves with the operator [`Self::factor_operator`] factored last.
    pub(crate) fn solve_operator(&self, rhs: &mut [f64]) {
        self.operator.as_ref().expect("the operator is factored before it is solved with").solve_in_place(rhs);
    }

    /// What a checkpoint keeps of the system.
    pub fn memory(&self) -> SystemMemory {
        SystemMemory {
            state: self.state.clone(),
            ledger: self.ledger,
            split_steps: self.split_steps,
            factored: self.operator.as_ref().and_then(|o| o.factored().cloned()),
        }
    }

    /// Takes back a [`Self::memory`] saved from a system of the same case; refuses one whose
    /// sizes do not fit this system.
    pub fn restore_memory(&mut self, memory: SystemMemory) -> Result<(), String> {
        let (n, m) = (self.body.dofs(), self.contact.points.len());
        let s = &memory.state;
        let fits = [&s.displacement, &s.velocity, &s.acceleration].iter().all(|v| v.len() == n)
            && s.contact.len() == m
            && s.plastic_increment.len() == m
            && (s.plastic_rate.is_empty() || s.plastic_rate.len() == m)
            && memory.factored.as_ref().is_none_or(|(_, k)| k.len() == m || k.len() == 2 * m);
        if !fits {
            return Err(format!(
                "the checkpoint's state ({} unknowns, {} contact points) does not fit this case ({n} unknowns, {m} \
                 contact points)",
                s.displacement.len(),
                s.contact.len()
            ));
        }
        if !(s.time.is_finite() && s.time >= 0.0) {
            return Err(format!("the checkpoint's time {} is not a time", crate::validate::shortest(s.time)));
        }
        if let Some((c0, stiffness)) = &memory.factored {
            self.factor_operator(*c0, stiffness)
                .map_err(|e| format!("cannot factor the checkpoint's operator: {e}"))?;
        }
        self.state = memory.state;
        self.ledger = memory.ledger.or(self.ledger);
        self.split_steps = memory.split_steps;
        Ok(())
    }

    /// Keeps an [`EnergyLedger`] from now on (costs one product with `K` per step).
    pub fn track_energy(&mut self) {
        let mut ledger = EnergyLedger::default();
        self.refresh_stored_energy(&mut ledger);
        ledger.initial = ledger.kinetic + ledger.strain + ledger.contact_elastic;
        self.ledger = Some(ledger);
    }

    /// The energy balance so far, if tracked.
    pub fn energy(&self) -> Option<EnergyLedger> {
        self.ledger
    }

    /// Adds the step from `old` to the current state (of length `dt`) to the ledger, if one is
    /// kept, and fails if the integrator has created more energy than `energy_tolerance`
    /// allows; a failed step leaves the ledger as it was.
    pub(crate) fn account_energy(&mut self, old: &State, dt: f64) -> Result<(), StepError> {
        if let Some(mut ledger) = self.ledger {
            ledger.add_step(&self.body, &self.contact, old, &self.state, dt);
            self.refresh_stored_energy(&mut ledger);
            if let Some(tolerance) = self.settings.energy_tolerance {
                // Early on, measured against the contact's strength energy rather than the little
                // work done so far.
                let reference = (ledger.initial + ledger.work_base + ledger.work_load).max(self.energy_scale);
                let share = -ledger.numerical() / reference;
                if share > tolerance {
                    return Err(StepError::EnergyCreated { share, tolerance });
                }
            }
            self.ledger = Some(ledger);
        }
        Ok(())
    }

    fn refresh_stored_energy(&self, ledger: &mut EnergyLedger) {
        ledger.refresh(&self.body, &self.contact, &self.state, &self.initial_traction, &self.initial_contact_force);
    }

    /// Counts a step (or half step) that had to be split in two to converge.
    pub(crate) fn count_split(&mut self) {
        self.split_steps += 1;
    }

    /// How many steps (or half steps) so far had to be split in two to converge.
    pub fn split_steps(&self) -> u64 {
        self.split_steps
    }

    /// Largest nodal imbalance of the total equation `M a + K u = f⁰ + f_c - f_c(0)` in the
    /// current state (N/m or Pa), computed when asked. Wilson's method enforces equilibrium at
    /// `t_n + θΔt`, so this is the interpolation error, not an accumulated drift.
    pub fn imbalance(&self) -> f64 {
        let s = &self.state;
        let mut imbalance = vec![0.0; self.body.dofs()];
        self.body.stiffness.mul_vec(&s.displacement, &mut imbalance);
        let load = self.body.load_at(s.time);
        for (i, e) in imbalance.iter_mut().enumerate() {
            *e = load.at(i) - self.initial_contact_force[i] - self.body.mass[i] * s.acceleration[i] - *e;
        }
        for (point, c) in self.contact.points.iter().zip(&s.contact) {
            point.scatter(point.weight * c.traction_t, &mut imbalance);
        }
        self.contact.scatter_normal_corrections(&s.displacement, &mut imbalance);
        max_abs(&imbalance)
    }
}

/// `Σ w (μ_k f_n)² / 2α_t`: the contact springs' energy at kinetic strength (J/m).
fn strength_energy(contact: &ContactBoundary) -> f64 {
    let points = contact.points.iter().zip(&contact.traction_n).enumerate();
    points
        .map(|(k, (point, f_n))| {
            point.weight * (contact.params(k).mu_k * f_n).powi(2) / (2.0 * contact.params(k).alpha_t)
        })
        .sum()
}

/// `½ M v²`: the body's kinetic energy moving as a whole at the drive's speed `v` (J/m), its mass
/// `M` that of the free degrees of freedom along one direction (`Σ m_i / 2` in the plane). The
/// scale of a body that a boundary moves and whose contact starts unpressed (no strength
/// energy): its first steps put in almost no work, and the rounding of the ledger's first
/// step would otherwise be judged against nothing.
fn drive_energy(body: &LinearBody, velocity_scale: f64) -> f64 {
    0.5 * (0.5 * body.mass.iter().sum::<f64>()) * velocity_scale * velocity_scale
}
