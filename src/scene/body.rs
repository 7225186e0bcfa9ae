//! An elastic body of finite elements with frictional contacts: the one scene behind the
//! paper's block and every mesh. [`build`] assembles a [`BodyDefinition`] and describes what a
//! frame shows of it ([`BodyShape`]).

use crate::case::Case;
use crate::dynamics::{LinearSolver, MainBody, Settings, System, condensation_pays};
use crate::fem::curve::Segment;
use crate::fem::equilibrium::Equilibrium;
use crate::fem::{Assembled, Dofs};
use crate::frame::{ContactInfo, Frame, Layout, MeshDrawing, Needs, NodeInfo, SceneKind, SegmentInfo};
use crate::scene::dynamic::{DynamicScene, Shape};
use crate::scene::interface::{RunError, step_error};
use crate::scene::sample::segment_sample;

/// How a body's contact points form segments (two Gauss points each), and what a frame shows
/// of it: the segments, the contacts' nodes and the drawn nodes.
pub struct BodyShape {
    dofs: Dofs,
    /// Segments over all contacts.
    segments: usize,
    /// The contacts' nodes, contact after contact, in order along each.
    surface_nodes: Vec<usize>,
    /// The mesh nodes the drawing draws, in its order.
    drawn: Vec<usize>,
    /// Each contact's points, where there are several.
    contact_points: Vec<std::ops::Range<usize>>,
}

/// A body scene.
pub type BodyScene = DynamicScene<BodyShape>;

/// What a scene shows beyond its assembly: its kind, the drawing, and the driving velocity.
pub struct Presentation {
    pub kind: SceneKind,
    /// The drawing and the mesh node of each drawn node.
    pub drawing: (MeshDrawing, Vec<usize>),
    /// The velocity that drives the scene (m/s), for the frames' and the catalog's scales.
    pub driving_velocity: f64,
    /// Each contact's name.
    pub contact_names: Vec<String>,
    /// Whether the body is a ring about the y axis (forces in N, not N/m).
    pub axisymmetric: bool,
}

/// Steps an assembled body as `case` asks, from rest in `equilibrium` where the body has weight
/// (each loaded contact point's stuck traction under gravity added to its `f0`).
pub fn build(
    case: &Case,
    assembled: Assembled,
    presentation: Presentation,
    equilibrium: Option<&Equilibrium>,
) -> Result<BodyScene, RunError> {
    let Assembled { body, mut contact, dofs, contacts, .. } = assembled;
    if let Some(equilibrium) = equilibrium {
        // An evolving contact starts from the normal traction its springs carry at rest.
        let initial: Vec<f64> = (0..contact.points.len())
            .map(|k| crate::case::mesh::initial_normal_traction(&contact, equilibrium, k))
            .collect();
        contact.traction_n = initial;
    }
    let mut contact_unknowns: Vec<usize> =
        contact.points.iter().flat_map(|p| p.tangential.terms().map(|(d, _)| d)).collect();
    contact_unknowns.sort_unstable();
    contact_unknowns.dedup();
    // A large body at a fixed step is condensed onto its contact; adaptive steps change τ
    // every attempt, and each new τ would need the body refactored.
    let fixed = case.time.method.fixed_implicit_steps(case.time.tolerance);
    // An evolving normal changes the operator's normal springs: the condensation keeps only the
    // tangential unknowns.
    let fixed = fixed && !contact.any_evolving();
    let linear_solver = if condensation_pays(body.dofs(), contact_unknowns.len()) && fixed {
        LinearSolver::Condensed
    } else {
        LinearSolver::Full
    };
    let settings = Settings {
        theta: case.time.theta,
        velocity_scale: presentation.driving_velocity.max(f64::MIN_POSITIVE),
        energy_tolerance: case.time.energy_guard(),
        linear_solver,
        ..Settings::default()
    };
    let surface_nodes: Vec<usize> = contacts
        .iter()
        .flat_map(|segments| segments.iter().map(|s| s.nodes[0]).chain(segments.last().map(|s| s.nodes[1])))
        .collect();
    let layout = layout(case, &contacts, &presentation);
    let several = contact.surfaces.len() > 1;
    let shape = BodyShape {
        dofs,
        segments: contacts.iter().map(Vec::len).sum(),
        surface_nodes,
        drawn: presentation.drawing.1,
        contact_points: if several { contact.surfaces.iter().map(|s| s.points.clone()).collect() } else { Vec::new() },
    };
    let mut system = System::new(body, contact, settings).map_err(|e| step_error(e, 0, 0.0, |p| p / 2))?;
    if let Some(equilibrium) = equilibrium {
        let tractions: Vec<f64> = system
            .state
            .contact
            .iter()
            .zip(&equilibrium.traction_t)
            .map(|(s, g)| if s.traction_n > 0.0 { g + s.traction_t } else { s.traction_t })
            .collect();
        system.start_from_tractions(&tractions);
    }
    Ok(DynamicScene::assemble(case, system, layout, shape))
}

/// The body's contacts, segments and surface nodes, named by the case's probes.
fn layout(case: &Case, contacts: &[Vec<Segment>], presentation: &Presentation) -> Layout {
    let centres: Vec<[f64; 2]> = contacts.iter().flatten().map(Segment::centre).collect();
    let node_positions: Vec<[f64; 2]> = contacts
        .iter()
        .flat_map(|chain| chain.iter().map(|s| s.ends[0]).chain(chain.last().map(|s| s.ends[1])))
        .collect();
    let resolved = |probes: &[crate::case::Probe], positions: &[[f64; 2]]| -> Vec<(usize, String)> {
        probes.iter().map(|p| (p.resolve(positions), p.name.clone())).collect()
    };
    let (segment_probes, node_probes) =
        (resolved(&case.probes.segments, &centres), resolved(&case.probes.nodes, &node_positions));
    let name_of = |probes: &[(usize, String)], index: usize| probes.iter().find(|p| p.0 == index).map(|p| p.1.clone());
    let mut segments = Vec::new();
    let mut surface_nodes = Vec::new();
    let mut infos = Vec::new();
    let evolving = case.scene.evolving_contacts();
    for ((chain, name), &evolving) in contacts.iter().zip(&presentation.contact_names).zip(&evolving) {
        for s in chain {
            let name = name_of(&segment_probes, segments.len());
            segments.push(SegmentInfo { left: s.arc[0], right: s.arc[1], name });
        }
        let arcs = chain.iter().map(|s| s.arc[0]).chain(chain.last().map(|s| s.arc[1]));
        let count = surface_nodes.len();
        for x in arcs {
            let name = name_of(&node_probes, surface_nodes.len());
            surface_nodes.push(NodeInfo { x, name });
        }
        let nodes = surface_nodes.len() - count;
        infos.push(ContactInfo { name: name.clone(), segments: chain.len(), nodes, evolving });
    }
    Layout {
        kind: presentation.kind,
        segments,
        surface_nodes,
        contacts: if infos.len() > 1 { infos } else { Vec::new() },
        mesh: Some(presentation.drawing.0.clone()),
        driving_velocity: presentation.driving_velocity,
        instantaneous_slip_rate: case.time.method.instantaneous_slip_rate(),
        axisymmetric: presentation.axisymmetric,
        evolving_normal: case.scene.has_evolving_normal(),
    }
}

impl Shape for BodyShape {
    fn segment_of_point(&self, point: usize) -> usize {
        point / 2
    }

    fn frame(&self, system: &System, needs: Needs, dt: f64) -> Frame {
        let s = &system.state;
        let points = &system.contact.points;
        let segments = (0..self.segments)
            .map(|k| {
                let mut sample = segment_sample(
                    system.contact.params(2 * k),
                    (2 * k..2 * k + 2).map(|p| (points[p].weight, s.contact[p], s.slip_rate(p, dt))),
                    needs.segment_state,
                );
                sample.open =
                    system.contact.evolves(2 * k) && (2 * k..2 * k + 2).all(|p| s.contact[p].traction_n <= 0.0);
                sample
            })
            .collect();
        let force = |range: std::ops::Range<usize>| -> f64 {
            points[range.clone()].iter().zip(&s.contact[range]).map(|(p, c)| p.weight * c.traction_t).sum()
        };
        let friction_force = force(0..points.len());
        let contact_forces = self.contact_points.iter().map(|r| force(r.clone())).collect();
        let displacement =
            |nodes: &[usize]| nodes.iter().map(|&n| self.dofs.displacement(n, &s.displacement, s.time)).collect();
        Frame {
            step: s.step,
            time: s.time,
            dt,
            segments,
            surface_nodes: if needs.surface_nodes { displacement(&self.surface_nodes) } else { Vec::new() },
            mesh: if needs.mesh { displacement(&self.drawn) } else { Vec::new() },
            friction_force,
            contact_forces,
            base_displacement: drive_displacement(&system.contact.surfaces[0].main_body, s.time),
            block: None,
        }
    }
}

/// The displacement of a main body along its drive (m): for a speed along the contact's
/// tangent (the block's base), its first component, the distance travelled along `t`; for a
/// velocity `[vx, vy]`, its component along the direction it first moves in (x for one that
/// never moves).
fn drive_displacement(main_body: &MainBody, t: f64) -> f64 {
    let u = main_body.motion.displacement_at(t);
    match main_body.motion.first_velocity() {
        Some(v) if !main_body.along_tangent => {
            let speed = v[0].hypot(v[1]);
            (u[0] * v[0] + u[1] * v[1]) / speed
        }
        _ => u[0],
    }
}
