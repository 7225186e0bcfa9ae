//! `kind = "block"`: the paper's §3 analysis, a plane-strain elastic block whose bottom is the
//! frictional contact against a moving rigid base.

use crate::case::{BlockSpec, Case};
use crate::dynamics::{LinearSolver, Settings, System, condensation_pays};
use crate::fem::{Block, PlaneStrain, StructuredMesh, assemble};
use crate::frame::{Frame, Layout, Needs, NodeInfo, SceneKind, SegmentInfo};
use crate::scene::dynamic::{DynamicScene, Shape};
use crate::scene::interface::{RunError, step_error};
use crate::scene::sample::segment_sample;

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

/// How the block's contact points form segments (two Gauss points each), and what a frame
/// shows of it: segments, the contact surface's nodes and the whole mesh.
pub struct BlockShape {
    mesh: StructuredMesh,
}

/// The paper's block.
pub type BlockScene = DynamicScene<BlockShape>;

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
        let fixed = case.time.method.fixed_implicit_steps(case.time.tolerance);
        let linear_solver = if condensation_pays(body.dofs(), spec.nx + 1) && fixed {
            LinearSolver::Condensed
        } else {
            LinearSolver::Full
        };
        let settings = Settings {
            theta: case.time.theta,
            velocity_scale: spec.base_velocity.abs().max(f64::MIN_POSITIVE),
            energy_tolerance: case.time.energy_guard(),
            linear_solver,
            ..Settings::default()
        };
        let shape = BlockShape { mesh };
        let system = System::new(body, contact, settings).map_err(|e| step_error(e, 0, 0.0, |p| p / 2))?;
        Ok(DynamicScene::assemble(case, system, layout(case, spec, mesh), shape))
    }
}

/// The block's segments and surface nodes, named by the case's probes.
fn layout(case: &Case, spec: &BlockSpec, mesh: StructuredMesh) -> Layout {
    let name_of =
        |probes: &[crate::case::Probe], index: usize| probes.iter().find(|p| p.index == index).map(|p| p.name.clone());
    let dx = mesh.dx();
    Layout {
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
        instantaneous_slip_rate: case.time.method.instantaneous_slip_rate(),
    }
}

impl BlockShape {
    fn node_displacement(&self, system: &System, id: usize) -> [f64; 2] {
        match self.mesh.node_dofs(id) {
            Some([x, y]) => [system.state.displacement[x], system.state.displacement[y]],
            None => [0.0, 0.0],
        }
    }
}

impl Shape for BlockShape {
    fn segment_of_point(&self, point: usize) -> usize {
        point / 2
    }

    fn frame(&self, system: &System, needs: Needs, dt: f64) -> Frame {
        let s = &system.state;
        let points = &system.contact.points;
        let segments = (0..self.mesh.nx)
            .map(|k| {
                segment_sample(
                    system.contact.params(2 * k),
                    (2 * k..2 * k + 2).map(|p| (points[p].weight, s.contact[p], s.slip_rate(p, dt))),
                    needs.segment_state,
                )
            })
            .collect();
        let friction_force = points.iter().zip(&s.contact).map(|(p, c)| p.weight * c.traction_t).sum();
        let surface_nodes = if needs.surface_nodes {
            (0..=self.mesh.nx).map(|i| self.node_displacement(system, self.mesh.surface_node(i))).collect()
        } else {
            Vec::new()
        };
        let mesh = if needs.mesh {
            (0..self.mesh.nodes()).map(|id| self.node_displacement(system, id)).collect()
        } else {
            Vec::new()
        };
        Frame {
            step: s.step,
            time: s.time,
            dt,
            segments,
            surface_nodes,
            mesh,
            friction_force,
            base_displacement: system.contact.surfaces[0].counter_body.motion.displacement_at(s.time)[0],
            block: None,
        }
    }
}
