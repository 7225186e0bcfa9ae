//! `kind = "spring_block"`: a rigid block on the frictional contact, pulled through a spring
//! whose far end moves at a constant velocity (Ozaki & Hashiguchi 2010).

use super::{
    Frame, Layout, Needs, RunError, Scene, SceneKind, SegmentInfo, advance_dynamics, advance_dynamics_adaptive,
    dynamics_for, segment_sample,
};
use crate::case::{Case, Integrator, SpringBlockSpec};
use crate::dynamics::sparse::SymmetricMatrix;
use crate::dynamics::{ContactBoundary, ContactPoint, Dynamics, LinearBody, StepControl, WilsonSettings};

/// `M ẍ + k x = k v t + f_t` per unit contact area, over a fixed base. It is the one-degree-of-
/// freedom case of the block's equation of motion and is integrated by the same [`Dynamics`].
pub struct SpringBlockScene {
    dynamics: Dynamics,
    layout: Layout,
    velocity: f64,
    /// The adaptive integrator and the slip-rate threshold whose crossings it locates.
    stepper: (Integrator, f64),
}

impl SpringBlockScene {
    pub fn new(case: &Case, spec: &SpringBlockSpec) -> Result<Self, RunError> {
        let body = LinearBody {
            mass: vec![spec.mass],
            stiffness: SymmetricMatrix::from_triplets(1, &[(0, 0, spec.stiffness)]),
            load_rate: vec![spec.stiffness * spec.velocity],
        };
        // The spring pulls the block along v; friction on the block opposes it.
        let contact = ContactBoundary {
            params: case.friction.clone(),
            points: vec![ContactPoint::single(0)],
            traction_n: vec![spec.normal_traction],
            base_velocity: 0.0,
            base_ramp: 0.0,
            loading_direction: if spec.velocity < 0.0 { 1.0 } else { -1.0 },
        };
        let settings = WilsonSettings {
            theta: case.time.theta,
            velocity_scale: spec.velocity.abs().max(f64::MIN_POSITIVE),
            energy_tolerance: case.time.energy_guard(),
            ..WilsonSettings::default()
        };
        let dynamics = dynamics_for(case, body, contact, settings, |_| 0)?;
        let layout = Layout {
            kind: SceneKind::SpringBlock,
            segments: vec![SegmentInfo { left: 0.0, right: 0.0, name: None }],
            surface_nodes: Vec::new(),
            mesh: None,
            driving_velocity: spec.velocity.abs(),
            instantaneous_slip_rate: case.time.instantaneous_slip_rate(),
        };
        let stepper = case.stepper();
        Ok(Self { dynamics, layout, velocity: spec.velocity, stepper })
    }

    /// The integrator, for tests that inspect it.
    pub fn dynamics(&self) -> &Dynamics {
        &self.dynamics
    }

    /// Mutable integrator, for tests that track its energy.
    pub fn dynamics_mut(&mut self) -> &mut Dynamics {
        &mut self.dynamics
    }
}

impl Scene for SpringBlockScene {
    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn time(&self) -> f64 {
        self.dynamics.state.time
    }

    fn advance(&mut self, dt: f64) -> Result<(), RunError> {
        advance_dynamics(&mut self.dynamics, dt, |_| 0)
    }

    fn advance_adaptive(&mut self, control: &mut StepControl, limit: f64) -> Result<f64, RunError> {
        advance_dynamics_adaptive(&mut self.dynamics, control, limit, self.stepper, |_| 0)
    }

    fn frame(&self, needs: Needs, dt: f64) -> Frame {
        let s = &self.dynamics.state;
        let sample = segment_sample(
            &self.dynamics.contact.params,
            std::iter::once((1.0, s.contact[0], s.slip_rate(0, dt))),
            needs.segment_state,
        );
        Frame {
            step: s.step,
            time: s.time,
            dt,
            segments: vec![sample],
            friction_force: s.contact[0].traction_t,
            base_displacement: self.velocity * s.time,
            block: Some([s.displacement[0], s.velocity[0]]),
            ..Frame::default()
        }
    }
}
