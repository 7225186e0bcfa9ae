//! The one type behind every scene with dynamics (the spring block, the paper's block): an
//! assembled [`System`] advanced by the case's [`Integrator`], observed through a [`Shape`]
//! that knows how the scene's contact points form segments and what a frame shows.

use crate::case::Case;
use crate::dynamics::{AdaptiveError, Integrator, Statistics, System};
use crate::frame::{Frame, Layout, Needs};
use crate::scene::interface::{RunError, Scene, SceneMemory, step_error};

/// What distinguishes one dynamic scene from another.
pub trait Shape: Send {
    /// The segment contact point `point` belongs to.
    fn segment_of_point(&self, point: usize) -> usize;
    /// Describes the current state of `system`; `dt` is the step just taken.
    fn frame(&self, system: &System, needs: Needs, dt: f64) -> Frame;
}

/// A scene with dynamics.
pub struct DynamicScene<S: Shape> {
    system: System,
    integrator: Box<dyn Integrator>,
    layout: Layout,
    shape: S,
}

impl<S: Shape> DynamicScene<S> {
    /// `system` stepped as `case` asks ([`Case::stepping`]).
    pub fn assemble(case: &Case, system: System, layout: Layout, shape: S) -> Self {
        let integrator = case.stepping().integrator(&system);
        Self { system, integrator, layout, shape }
    }

    /// The assembled model, for tests that inspect it.
    pub fn system(&self) -> &System {
        &self.system
    }

    /// Mutable model, for tests that set initial conditions or track energy.
    pub fn system_mut(&mut self) -> &mut System {
        &mut self.system
    }
}

impl<S: Shape> Scene for DynamicScene<S> {
    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn time(&self) -> f64 {
        self.system.state.time
    }

    /// Advances by one step of the integrator; a failure names the step, the time it started
    /// from and the segment of the contact point involved.
    fn advance(&mut self, limit: f64) -> Result<f64, RunError> {
        let (step, time) = (self.system.state.step + 1, self.system.state.time);
        let shape = &self.shape;
        self.integrator.advance(&mut self.system, limit).map_err(|e| match e {
            AdaptiveError::Step(e) => step_error(e, step, time, |p| shape.segment_of_point(p)),
            e @ AdaptiveError::StepTooSmall { .. } => RunError { step, time, segment: None, message: e.to_string() },
        })
    }

    fn longest_next_step(&self, limit: f64) -> f64 {
        self.integrator.longest_next_step(limit)
    }

    fn statistics(&self) -> Statistics {
        self.integrator.statistics()
    }

    fn frame(&self, needs: Needs, dt: f64) -> Frame {
        self.shape.frame(&self.system, needs, dt)
    }

    fn memory(&self) -> SceneMemory {
        SceneMemory::Dynamic { system: Box::new(self.system.memory()), integrator: Box::new(self.integrator.memory()) }
    }

    /// The system first, so that the integrator's memory is checked against the state it
    /// continues.
    fn restore(&mut self, memory: SceneMemory) -> Result<(), String> {
        let SceneMemory::Dynamic { system, integrator } = memory else {
            return Err("the checkpoint holds a point scene, the case a body".into());
        };
        self.system.restore_memory(*system)?;
        self.integrator.restore(&self.system, *integrator)
    }
}
