//! `kind = "spring_block"`: a rigid block on the frictional contact, pulled through a spring
//! whose far end moves at a constant velocity (Ozaki & Hashiguchi 2010).

use crate::case::{Case, SpringBlockSpec};
use crate::dynamics::{ContactBoundary, ContactPoint, LinearBody, Load, LoadHistory, MainBody, Settings, System};
use crate::frame::{Frame, Layout, Needs, SceneKind, SegmentInfo};
use crate::linalg::sparse::SymmetricMatrix;
use crate::scene::dynamic::{DynamicScene, Shape};
use crate::scene::interface::{RunError, step_error};
use crate::scene::sample::segment_sample;

/// The spring block's one contact point and what a frame shows of it: the block's
/// displacement and velocity, and the spring's far end.
pub struct SpringBlockShape {
    /// Velocity of the spring's far end (m/s).
    velocity: f64,
}

/// `M ẍ + k x = k v t + f_t` per unit contact area, over a fixed base. It is the one-degree-of-
/// freedom case of the block's equation of motion and is integrated by the same [`System`].
pub type SpringBlockScene = DynamicScene<SpringBlockShape>;

impl SpringBlockScene {
    pub fn new(case: &Case, spec: &SpringBlockSpec) -> Result<Self, RunError> {
        let mut body = LinearBody::new(vec![spec.mass], SymmetricMatrix::from_triplets(1, &[(0, 0, spec.stiffness)]));
        body.loads.push(Load { pattern: vec![spec.stiffness * spec.velocity], history: LoadHistory::Linear });
        // The spring pulls the block along v; friction on the block opposes it.
        let point = ContactPoint::single(0, if spec.velocity < 0.0 { 1.0 } else { -1.0 });
        let contact = ContactBoundary::single(
            case.friction.clone(),
            MainBody::at_rest(),
            vec![point],
            vec![spec.normal_traction],
        );
        let settings = Settings {
            theta: case.time.theta,
            velocity_scale: spec.velocity.abs().max(f64::MIN_POSITIVE),
            energy_tolerance: case.time.energy_guard(),
            ..Settings::default()
        };
        let system = System::new(body, contact, settings).map_err(|e| step_error(e, 0, 0.0, |_| 0))?;
        let layout = Layout {
            kind: SceneKind::SpringBlock,
            segments: vec![SegmentInfo { left: 0.0, right: 0.0, name: None }],
            surface_nodes: Vec::new(),
            contacts: Vec::new(),
            mesh: None,
            driving_velocity: spec.velocity.abs(),
            instantaneous_slip_rate: case.time.method.instantaneous_slip_rate(),
            axisymmetric: false,
            evolving_normal: false,
        };
        Ok(DynamicScene::assemble(case, system, layout, SpringBlockShape { velocity: spec.velocity }))
    }
}

impl Shape for SpringBlockShape {
    fn segment_of_point(&self, _point: usize) -> usize {
        0
    }

    fn frame(&self, system: &System, needs: Needs, dt: f64) -> Frame {
        let s = &system.state;
        let sample = segment_sample(
            system.contact.params(0),
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
