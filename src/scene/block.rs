//! `kind = "block"`: the paper's §3 analysis, a plane-strain elastic block whose bottom is the
//! frictional contact against a moving rigid base.

use super::{
    Frame, Layout, Needs, NodeInfo, RunError, Scene, SceneKind, SegmentInfo, advance_dynamics,
    advance_dynamics_adaptive, dynamics_for, segment_sample,
};
use crate::case::{BlockSpec, Case, Integrator};
use crate::dynamics::{Dynamics, LinearSolver, StepControl, WilsonSettings, condensation_pays};
use crate::fem::{Block, PlaneStrain, StructuredMesh, assemble};

/// Peak memory (bytes) a block of `nx × ny` elements is expected to need: a base of 16 MB plus
/// 200 B × log2(n) per degree of freedom `n = 2 (nx+1)(ny+1)`, the sparse factor's fill growing
/// like `n log n`, plus three dense `k × k` matrices where the contact's `k = nx + 1` unknowns
/// are condensed. Fitted to the peak RSS of 1000×100 measured here (692 MB; the estimate is
/// 8 % higher); at 300×30 and 100×10 it is 12 % lower and 40 % higher (79 MB and 15 MB
/// measured). Adaptive runs, which never condense, need less.
pub fn estimated_memory(nx: usize, ny: usize) -> (f64, f64) {
    let dofs = 2.0 * (nx as f64 + 1.0) * (ny as f64 + 1.0);
    let contact = nx as f64 + 1.0;
    let condensed =
        if condensation_pays(dofs as usize, nx.saturating_add(1)) { 3.0 * 8.0 * contact * contact } else { 0.0 };
    (dofs, 16.0e6 + 200.0 * dofs * dofs.log2() + condensed)
}

pub struct BlockScene {
    dynamics: Dynamics,
    mesh: StructuredMesh,
    layout: Layout,
    /// The adaptive integrator and the slip-rate threshold whose crossings it locates.
    stepper: (Integrator, f64),
}

impl BlockScene {
    pub fn new(case: &Case, spec: &BlockSpec) -> Result<Self, RunError> {
        let mesh = StructuredMesh { width: spec.width, height: spec.height, nx: spec.nx, ny: spec.ny };
        let material = PlaneStrain { youngs_modulus: spec.youngs_modulus, poisson_ratio: spec.poisson_ratio };
        let Block { body, contact, .. } = assemble(
            mesh,
            material,
            spec.density,
            case.friction.clone(),
            |x| spec.normal_traction.at(x, spec.width),
            spec.base_velocity,
            spec.base_ramp_time,
        );
        // A large body at a fixed step is condensed onto its contact; adaptive steps change τ
        // every attempt, and each new τ would need the body refactored.
        let linear_solver = if condensation_pays(body.dofs(), spec.nx + 1) && case.time.fixed_implicit_steps() {
            LinearSolver::Condensed
        } else {
            LinearSolver::Full
        };
        let settings = WilsonSettings {
            theta: case.time.theta,
            velocity_scale: spec.base_velocity.abs().max(f64::MIN_POSITIVE),
            energy_tolerance: case.time.energy_guard(),
            linear_solver,
            ..WilsonSettings::default()
        };
        let dynamics = dynamics_for(case, body, contact, settings, |p| p / 2)?;
        let name_of = |probes: &[crate::case::Probe], index: usize| {
            probes.iter().find(|p| p.index == index).map(|p| p.name.clone())
        };
        let dx = mesh.dx();
        let layout = Layout {
            kind: SceneKind::Block,
            segments: (0..mesh.nx)
                .map(|k| SegmentInfo {
                    left: k as f64 * dx,
                    right: (k + 1) as f64 * dx,
                    name: name_of(&case.probes.segments, k),
                })
                .collect(),
            surface_nodes: (0..=mesh.nx)
                .map(|i| NodeInfo { x: i as f64 * dx, name: name_of(&case.probes.nodes, i) })
                .collect(),
            mesh: Some(mesh),
            driving_velocity: spec.base_velocity.abs(),
            instantaneous_slip_rate: case.time.instantaneous_slip_rate(),
        };
        let stepper = case.stepper();
        Ok(Self { dynamics, mesh, layout, stepper })
    }

    /// The integrator, for tests that inspect it.
    pub fn dynamics(&self) -> &Dynamics {
        &self.dynamics
    }

    /// Mutable integrator, for tests that set initial conditions.
    pub fn dynamics_mut(&mut self) -> &mut Dynamics {
        &mut self.dynamics
    }

    fn node_displacement(&self, id: usize) -> [f64; 2] {
        match self.mesh.node_dofs(id) {
            Some([x, y]) => [self.dynamics.state.displacement[x], self.dynamics.state.displacement[y]],
            None => [0.0, 0.0],
        }
    }
}

impl Scene for BlockScene {
    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn time(&self) -> f64 {
        self.dynamics.state.time
    }

    fn advance(&mut self, dt: f64) -> Result<(), RunError> {
        advance_dynamics(&mut self.dynamics, dt, |p| p / 2)
    }

    fn advance_adaptive(&mut self, control: &mut StepControl, limit: f64) -> Result<f64, RunError> {
        advance_dynamics_adaptive(&mut self.dynamics, control, limit, self.stepper, |p| p / 2)
    }

    fn frame(&self, needs: Needs, dt: f64) -> Frame {
        let d = &self.dynamics;
        let s = &d.state;
        let points = &d.contact.points;
        let segments = (0..self.mesh.nx)
            .map(|k| {
                segment_sample(
                    &d.contact.params,
                    (2 * k..2 * k + 2).map(|p| (points[p].weight, s.contact[p], s.slip_rate(p, dt))),
                    needs.segment_state,
                )
            })
            .collect();
        let friction_force = points.iter().zip(&s.contact).map(|(p, c)| p.weight * c.traction_t).sum();
        let surface_nodes = if needs.surface_nodes {
            (0..=self.mesh.nx).map(|i| self.node_displacement(self.mesh.surface_node(i))).collect()
        } else {
            Vec::new()
        };
        let mesh =
            if needs.mesh { (0..self.mesh.nodes()).map(|id| self.node_displacement(id)).collect() } else { Vec::new() };
        Frame {
            step: s.step,
            time: s.time,
            dt,
            segments,
            surface_nodes,
            mesh,
            friction_force,
            base_displacement: d.contact.base_displacement_at(s.time),
            block: None,
        }
    }
}
