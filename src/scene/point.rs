//! `kind = "point"`: the friction law alone, driven by a prescribed relative sliding velocity.

use crate::case::PointSpec;
use crate::dynamics::NormalBehaviour;
use crate::frame::{Frame, Layout, Needs, SceneKind, SegmentInfo};
use crate::friction::{ContactState, FrictionParams, update, update_evolving};
use crate::scene::interface::{RunError, Scene, SceneMemory, friction_error};
use crate::scene::sample::segment_sample;

/// One contact point under a piecewise-constant relative sliding velocity `(v̄_t, v̄_n)` (held at
/// 0 after the last phase), its normal traction held or evolving (`ḟ_n = -α_n v̄_n`). Steps
/// that straddle a phase change are split there, so each update sees a constant velocity.
pub struct PointScene {
    params: FrictionParams,
    /// `(end, v̄_t, v̄_n)` of each phase.
    phases: Vec<(f64, f64, f64)>,
    /// The initial normal traction, where it evolves.
    evolving: Option<f64>,
    layout: Layout,
    state: ContactState,
    time: f64,
    step: u64,
    last_increment: f64,
    relative_slip: f64,
    /// `∫ v̄_n dt` (m): the normal opening since the start.
    normal_opening: f64,
}

impl PointScene {
    pub fn new(params: FrictionParams, spec: PointSpec) -> Self {
        let first = spec.phases.iter().map(|p| p.velocity).find(|v| *v != 0.0).unwrap_or(-1.0);
        // Sliding v̄_t > 0 loads f_t negatively (ḟ = -α_t v̄): f0 points against the first motion.
        let state = ContactState::initial(&params, spec.normal_traction, -first);
        let mut start = 0.0;
        let phases = spec
            .phases
            .iter()
            .map(|p| {
                start += p.duration;
                (start, p.velocity, p.normal_velocity)
            })
            .collect();
        let evolving = (spec.normal == NormalBehaviour::Evolving).then_some(spec.normal_traction);
        let layout = Layout {
            kind: SceneKind::Point,
            segments: vec![SegmentInfo { left: 0.0, right: 0.0, name: None }],
            surface_nodes: Vec::new(),
            contacts: Vec::new(),
            mesh: None,
            driving_velocity: spec.phases.iter().fold(0.0_f64, |m, p| m.max(p.velocity.abs())),
            instantaneous_slip_rate: false,
            axisymmetric: false,
            evolving_normal: spec.normal == NormalBehaviour::Evolving,
        };
        Self {
            params,
            phases,
            evolving,
            layout,
            state,
            time: 0.0,
            step: 0,
            last_increment: 0.0,
            relative_slip: 0.0,
            normal_opening: 0.0,
        }
    }

    /// The contact state now.
    pub fn state(&self) -> &ContactState {
        &self.state
    }

    /// The phase at time `t`: its end and relative velocities `(v̄_t, v̄_n)`.
    fn velocity_after(&self, t: f64) -> (f64, f64, f64) {
        for &(end, velocity, normal) in &self.phases {
            if t < end {
                return (end, velocity, normal);
            }
        }
        (f64::INFINITY, 0.0, 0.0)
    }
}

impl Scene for PointScene {
    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn advance(&mut self, dt: f64) -> Result<f64, RunError> {
        let target = self.time + dt;
        let mut t = self.time;
        let mut increment = 0.0;
        while t < target {
            let (end, velocity, normal) = self.velocity_after(t);
            // Snap to a phase end that is within rounding of the step's end.
            let stop = if end < target - 1e-12 * target.max(1.0) { end } else { target };
            let h = stop - t;
            let updated = match self.evolving {
                None => update(&self.params, &self.state, velocity * h, h),
                Some(initial) => {
                    self.normal_opening += normal * h;
                    let traction_n = initial - self.params.alpha_n * self.normal_opening;
                    update_evolving(&self.params, &self.state, velocity * h, traction_n, h, None)
                }
            }
            .map_err(|e| friction_error(e, &self.state, self.step + 1, t))?;
            self.state = updated.state;
            self.relative_slip += velocity * h;
            increment += updated.plastic_increment;
            t = stop;
        }
        self.time = target;
        self.step += 1;
        self.last_increment = increment;
        Ok(dt)
    }

    fn memory(&self) -> SceneMemory {
        SceneMemory::Point {
            state: self.state,
            time: self.time,
            step: self.step,
            last_increment: self.last_increment,
            relative_slip: self.relative_slip,
            normal_opening: self.normal_opening,
        }
    }

    fn restore(&mut self, memory: SceneMemory) -> Result<(), String> {
        let SceneMemory::Point { state, time, step, last_increment, relative_slip, normal_opening } = memory else {
            return Err("the checkpoint holds a body, the case a point scene".into());
        };
        if !(time.is_finite() && time >= 0.0) {
            return Err(format!("the checkpoint's time {} is not a time", crate::validate::shortest(time)));
        }
        (self.state, self.time, self.step, self.last_increment, self.relative_slip, self.normal_opening) =
            (state, time, step, last_increment, relative_slip, normal_opening);
        Ok(())
    }

    fn frame(&self, needs: Needs, dt: f64) -> Frame {
        let mut sample = segment_sample(
            &self.params,
            std::iter::once((1.0, self.state, if dt > 0.0 { self.last_increment / dt } else { 0.0 })),
            needs.segment_state,
        );
        sample.open = self.evolving.is_some() && self.state.traction_n <= 0.0;
        Frame {
            step: self.step,
            time: self.time,
            dt,
            segments: vec![sample],
            friction_force: self.state.traction_t,
            base_displacement: -self.relative_slip,
            ..Frame::default()
        }
    }
}
