//! `kind = "mesh"`: a body drawn in Gmsh. The case names the mesh's physical groups: materials on
//! surfaces, boundaries (fixed, moving or loaded) and frictional contacts on curves. The mesh
//! is read and every group resolved when the case is loaded, so that a wrong name is refused
//! before anything runs, with the groups the mesh has.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::Deserialize;

use crate::case::profile::ProfileSpec;
use crate::dynamics::{MainBody, Motion, NormalBehaviour};
use crate::fem::curve::{CurvePoint, segments};
use crate::fem::equilibrium::{Equilibrium, under_gravity};
use crate::fem::stiffest::{EdgeSpring, cell_frequency, largest};
use crate::fem::{
    BodyDefinition, Constraint, ContactDefinition, Material, Members, Mesh, PlaneStrain, Traction, TractionLoad,
};
use crate::friction::FrictionParams;
use crate::validate::{Checker, Violation, shortest};

/// `[scene]` with `kind = "mesh"`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// The Gmsh file (MSH 4.1 ASCII or binary, MSH 2.2 ASCII), relative to the case file.
    pub file: String,
    /// `[[scene.materials]]`: the material of each surface group.
    pub materials: Vec<MaterialSpec>,
    /// `[[scene.boundaries]]`: fixed, moving or loaded curves (eq. 10's `S_v` and `S_t`); the rest
    /// of the boundary is free.
    #[serde(default)]
    pub boundaries: Vec<BoundarySpec>,
    /// `[[scene.contacts]]`: the frictional contacts (`S_c`).
    pub contacts: Vec<ContactSpec>,
    /// The mesh is the half-plane `r = x ≥ 0`, `z = y` of a body of revolution about the y
    /// axis ([`crate::fem::axisymmetric`]); forces are then in N. Default false: plane strain.
    #[serde(default)]
    pub axisymmetric: bool,
    /// The acceleration of gravity `[gx, gy]` (m/s²): the body starts in static equilibrium
    /// under its weight with its contacts stuck ([`crate::fem::equilibrium`]). Default none.
    pub gravity: Option<[f64; 2]>,
    /// The mesh and what the case's names resolve to, once loaded ([`MeshSpec::load`]).
    #[serde(skip)]
    pub loaded: Option<Arc<LoadedMesh>>,
}

/// `[[scene.materials]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// A surface group of the mesh; left out, every cell no other material names (a mesh
    /// whose surface has no physical group, as Gmsh writes with `Mesh.SaveAll`).
    pub group: Option<String>,
    /// `E` (Pa).
    pub youngs_modulus: f64,
    /// `ν` (-), in [0, 0.5).
    pub poisson_ratio: f64,
    /// `ρ` (kg/m³).
    pub density: f64,
}

/// Which displacement components a boundary prescribes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
pub enum Components {
    #[serde(rename = "x")]
    X,
    #[serde(rename = "y")]
    Y,
    #[serde(rename = "xy")]
    XY,
}

impl Components {
    pub fn mask(self) -> [bool; 2] {
        match self {
            Components::X => [true, false],
            Components::Y => [false, true],
            Components::XY => [true, true],
        }
    }
}

/// A velocity: a number (one component, or a speed along a contact's tangent) or `[vx, vy]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum VelocitySpec {
    Scalar(f64),
    Vector([f64; 2]),
}

/// One phase of a velocity history.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PhaseSpec {
    /// The velocity held (m/s).
    pub velocity: VelocitySpec,
    /// How long (s); the last phase may leave it out to last to the end.
    pub duration: Option<f64>,
}

/// `[[scene.boundaries]]`: exactly one of `fixed`, `velocity`, `phases`, `traction`, `pressure`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundarySpec {
    /// A curve (or point) group of the mesh.
    pub group: String,
    /// Held still in these components.
    pub fixed: Option<Components>,
    /// Moved at this velocity (m/s) from rest, after `ramp_time`.
    pub velocity: Option<VelocitySpec>,
    /// Moved through these phases of velocity.
    pub phases: Option<Vec<PhaseSpec>>,
    /// With `velocity` or `phases`: the components they prescribe (default `"xy"` for vectors).
    pub components: Option<Components>,
    /// A traction `[tx, ty]` (Pa) on the curve.
    pub traction: Option<[f64; 2]>,
    /// A pressure (Pa) pushing into the body along the curve's inward normal.
    pub pressure: Option<f64>,
    /// Every change of velocity, or the traction's rise from 0, is spread over this time (s);
    /// default 0: at once.
    #[serde(default)]
    pub ramp_time: f64,
    /// A traction or pressure acts this long (s), then falls back to 0 over `ramp_time`;
    /// default: to the end.
    pub duration: Option<f64>,
}

/// `[[scene.contacts]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// A curve group of the mesh: one open chain of boundary edges.
    pub group: String,
    /// The main body's velocity (m/s): a number along the contact's tangent, or `[vx, vy]`;
    /// default 0 (held still).
    pub base_velocity: Option<VelocitySpec>,
    /// Or its phases.
    pub base_phases: Option<Vec<PhaseSpec>>,
    /// Every change of the main body's velocity is spread over this time (s); default 0.
    #[serde(default)]
    pub base_ramp_time: f64,
    /// The normal traction along the contact (Pa): held constant, or its initial value.
    pub normal_traction: ProfileSpec,
    /// `"held"` (default) or `"evolving"`: whether `f_n` follows `ḟ_n = -α_n v̄_n`.
    #[serde(default)]
    pub normal: NormalBehaviour,
    /// The initial normal gap (m) of an evolving contact, where it does not yet touch.
    pub gap: Option<ProfileSpec>,
    /// This contact's friction constants where they differ from `[friction]`.
    pub friction: Option<toml::Table>,
}

/// A mesh read, and the case's names resolved on it.
pub struct LoadedMesh {
    /// The file as found (the case's folder joined with `file`).
    pub path: PathBuf,
    /// A digest of the file's bytes, which stands for the mesh in the case's `Debug` form.
    pub digest: u64,
    pub mesh: Mesh,
    /// Each cell's material ([`MeshSpec::materials`] index).
    pub cell_material: Vec<usize>,
    /// Each boundary's nodes, and for loaded ones the chain.
    pub boundary_nodes: Vec<Vec<usize>>,
    pub boundary_chains: Vec<Option<Vec<usize>>>,
    /// Each contact's chain, and its friction constants.
    pub contact_chains: Vec<Vec<usize>>,
    pub contact_params: Vec<FrictionParams>,
    /// The static equilibrium under `gravity`, every contact stuck; `None` without gravity.
    pub equilibrium: Option<Equilibrium>,
}

/// Left out of a case's `Debug` form, which names the run: the file's digest stands for the
/// mesh.
impl std::fmt::Debug for LoadedMesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "mesh {:016x}", self.digest)
    }
}

impl VelocitySpec {
    fn vector(self) -> [f64; 2] {
        match self {
            VelocitySpec::Scalar(v) => [v, 0.0],
            VelocitySpec::Vector(v) => v,
        }
    }

    fn is_scalar(self) -> bool {
        matches!(self, VelocitySpec::Scalar(_))
    }

    fn finite(self) -> bool {
        self.vector().iter().all(|v| v.is_finite())
    }
}

/// A velocity history from a constant velocity or phases, every change spread over `ramp`;
/// `place` puts a phase's velocity into x and y.
fn motion(
    velocity: Option<VelocitySpec>,
    phases: Option<&[PhaseSpec]>,
    ramp: f64,
    place: impl Fn(VelocitySpec) -> [f64; 2],
) -> Motion {
    match (velocity, phases) {
        (_, Some(phases)) => {
            Motion::phases(&phases.iter().map(|p| (place(p.velocity), p.duration)).collect::<Vec<_>>(), ramp)
        }
        (Some(v), None) => Motion::constant(place(v), ramp),
        (None, None) => Motion::at_rest(),
    }
}

impl BoundarySpec {
    /// The prescribed components and their motion, for a boundary that prescribes motion.
    pub fn constraint(&self) -> Option<([bool; 2], Motion)> {
        if let Some(fixed) = self.fixed {
            return Some((fixed.mask(), Motion::at_rest()));
        }
        if self.velocity.is_none() && self.phases.is_none() {
            return None;
        }
        let components = self.components.unwrap_or(Components::XY);
        let place = |v: VelocitySpec| match (v, components) {
            (VelocitySpec::Scalar(v), Components::Y) => [0.0, v],
            (v, _) => v.vector(),
        };
        Some((components.mask(), motion(self.velocity, self.phases.as_deref(), self.ramp_time, place)))
    }

    fn check(&self, c: &mut Checker<'_>) {
        let kinds = [
            self.fixed.is_some(),
            self.velocity.is_some(),
            self.phases.is_some(),
            self.traction.is_some(),
            self.pressure.is_some(),
        ];
        if kinds.iter().filter(|&&k| k).count() != 1 {
            c.fail(
                "group",
                format!("{:?}", self.group),
                "must have exactly one of fixed, velocity, phases, traction or pressure",
            );
            return;
        }
        c.non_negative("ramp_time", self.ramp_time);
        if let Some(duration) = self.duration {
            if self.traction.is_none() && self.pressure.is_none() {
                c.fail("duration", duration, "applies to a traction or a pressure only");
            } else if !(duration.is_finite() && duration >= self.ramp_time && duration > 0.0) {
                let rule = format!(
                    "must be finite, positive and at least {} = {} (the load rises over it)",
                    c.key("ramp_time"),
                    self.ramp_time
                );
                c.fail("duration", duration, rule);
            }
        }
        let velocities: Vec<VelocitySpec> =
            self.velocity.into_iter().chain(self.phases.iter().flatten().map(|p| p.velocity)).collect();
        if let (true, Some(components)) = (velocities.is_empty(), self.components) {
            c.fail("components", format!("{components:?}"), "applies to velocity or phases only");
        }
        for (i, v) in velocities.iter().enumerate() {
            let key = if self.velocity.is_some() { "velocity".to_string() } else { format!("phases[{i}].velocity") };
            if !v.finite() {
                c.fail(&key, format!("{:?}", v.vector()), "must be finite");
            }
            match (v.is_scalar(), self.components) {
                (true, Some(Components::X | Components::Y)) | (false, None | Some(Components::XY)) => {}
                (true, _) => c.fail(
                    &key,
                    format!("{:?}", v.vector()[0]),
                    "is one number: say which component it moves, components = \"x\" or \"y\" (or give [vx, vy])",
                ),
                (false, Some(k)) => c.fail(
                    &key,
                    format!("{:?}", v.vector()),
                    format!("is a vector, but components = {k:?} prescribes one component: give a number"),
                ),
            }
        }
        check_phases(self.phases.as_deref(), "phases", c);
        if let Some(t) = self.traction {
            for (i, v) in t.iter().enumerate() {
                c.finite(&format!("traction[{i}]"), *v);
            }
        }
        if let Some(p) = self.pressure {
            c.finite("pressure", p);
        }
    }
}

/// Every phase but the last has a positive duration; the last may leave it out.
fn check_phases(phases: Option<&[PhaseSpec]>, key: &str, c: &mut Checker<'_>) {
    let Some(phases) = phases else { return };
    if phases.is_empty() {
        c.fail(key, "[]", "must list at least one {velocity, duration} phase");
    }
    for (i, phase) in phases.iter().enumerate() {
        match phase.duration {
            Some(d) => c.positive(&format!("{key}[{i}].duration"), d),
            None if i + 1 < phases.len() => {
                c.fail(&format!("{key}[{i}].duration"), "none", "is needed: only the last phase may last to the end")
            }
            None => {}
        }
    }
}

impl ContactSpec {
    /// How the contact's main body moves.
    pub fn main_body(&self) -> MainBody {
        let along_tangent = self
            .base_velocity
            .or(self.base_phases.as_ref().and_then(|p| p.first()).map(|p| p.velocity))
            .is_none_or(VelocitySpec::is_scalar);
        MainBody {
            motion: motion(self.base_velocity, self.base_phases.as_deref(), self.base_ramp_time, VelocitySpec::vector),
            along_tangent,
        }
    }

    fn check(&self, c: &mut Checker<'_>) {
        c.non_negative("base_ramp_time", self.base_ramp_time);
        if self.base_velocity.is_some() && self.base_phases.is_some() {
            c.fail("base_phases", "[...]", "cannot be given with base_velocity: give one of them");
        }
        let velocities: Vec<VelocitySpec> =
            self.base_velocity.into_iter().chain(self.base_phases.iter().flatten().map(|p| p.velocity)).collect();
        for v in &velocities {
            if !v.finite() {
                c.fail("base_velocity", format!("{:?}", v.vector()), "must be finite");
            }
        }
        if velocities.windows(2).any(|w| w[0].is_scalar() != w[1].is_scalar()) {
            c.fail(
                "base_phases",
                "[...]",
                "must give every velocity the same way: all numbers (along the contact) or all [vx, vy]",
            );
        }
        check_phases(self.base_phases.as_deref(), "base_phases", c);
        let prefix = c.key("normal_traction");
        let mut traction = Checker::new(&prefix);
        self.normal_traction.check(&mut traction);
        c.absorb(traction);
        if let Some(gap) = &self.gap {
            if matches!(gap, ProfileSpec::Lithostatic { .. }) {
                c.fail(
                    "gap",
                    "{kind = \"lithostatic\", ...}",
                    "must be uniform, linear or a table: a gap is a distance (m), not a stress",
                );
            }
            if self.normal != NormalBehaviour::Evolving {
                let rule = format!("needs {} = \"evolving\": a held contact has no gap", c.key("normal"));
                c.fail("gap", "{...}", rule);
            }
            let prefix = c.key("gap");
            let mut checker = Checker::new(&prefix);
            gap.check(&mut checker);
            c.absorb(checker);
        }
        if self.normal == NormalBehaviour::Evolving && !velocities.iter().all(|v| v.is_scalar()) {
            c.fail(
                "base_velocity",
                "[vx, vy]",
                "of an evolving contact must be a number, a speed along the contact: its main body does not press \
                 it or pull away along its normal",
            );
        }
    }
}

impl MaterialSpec {
    fn check(&self, c: &mut Checker<'_>) {
        c.positive("youngs_modulus", self.youngs_modulus);
        if c.finite("poisson_ratio", self.poisson_ratio) && !(0.0..0.5).contains(&self.poisson_ratio) {
            c.fail("poisson_ratio", self.poisson_ratio, "must lie in [0, 0.5)");
        }
        c.positive("density", self.density);
    }

    fn material(&self) -> Material {
        Material {
            elasticity: PlaneStrain { youngs_modulus: self.youngs_modulus, poisson_ratio: self.poisson_ratio },
            density: self.density,
        }
    }
}

impl MeshSpec {
    /// The rules that need no mesh, under `scene`.
    pub fn check(&self, c: &mut Checker<'_>) {
        if self.materials.is_empty() {
            c.fail("materials", "[]", "must give at least one material: [[scene.materials]] with a surface group");
        }
        if self.contacts.is_empty() {
            c.fail("contacts", "[]", "must give at least one contact: [[scene.contacts]] with a curve group");
        }
        for (i, m) in self.materials.iter().enumerate() {
            let prefix = c.key(&format!("materials[{i}]"));
            let mut inner = Checker::new(&prefix);
            m.check(&mut inner);
            c.absorb(inner);
        }
        for (i, b) in self.boundaries.iter().enumerate() {
            let prefix = c.key(&format!("boundaries[{i}]"));
            let mut inner = Checker::new(&prefix);
            b.check(&mut inner);
            c.absorb(inner);
        }
        for (i, contact) in self.contacts.iter().enumerate() {
            let prefix = c.key(&format!("contacts[{i}]"));
            let mut inner = Checker::new(&prefix);
            contact.check(&mut inner);
            c.absorb(inner);
        }
        if let Some(g) = self.gravity {
            for (i, v) in g.iter().enumerate() {
                c.finite(&format!("gravity[{i}]"), *v);
            }
        }
    }

    /// The mesh as loaded; panics before [`Self::load`].
    pub fn loaded(&self) -> &LoadedMesh {
        self.loaded.as_deref().expect("a mesh case is loaded before it is used")
    }

    /// Reads the mesh (`file` relative to `dir`) and resolves every group the case names on it,
    /// with `friction` (`[friction]`) as every contact's default. `Err` is a file the reader
    /// refuses (its message names the file and where); the violations are the case's.
    pub fn load(&mut self, dir: &Path, friction: &toml::Table) -> Result<Vec<Violation>, String> {
        let path = dir.join(&self.file);
        let (mesh, digest) = crate::fem::gmsh::read_with_digest(&path).map_err(|e| e.to_string())?;
        let mut c = Checker::new("scene");
        if self.axisymmetric {
            check_half_plane(&mesh, &mut c);
        }
        let cell_material = self.cell_materials(&mesh, &mut c);
        let mut boundary_nodes = Vec::new();
        let mut boundary_chains = Vec::new();
        for (i, b) in self.boundaries.iter().enumerate() {
            let key = format!("boundaries[{i}].group");
            let loaded = b.traction.is_some() || b.pressure.is_some();
            boundary_chains.push(if loaded { chain(&mesh, &b.group, &key, &mut c) } else { None });
            boundary_nodes.push(nodes_of(&mesh, &b.group, &key, &mut c));
        }
        let mut contact_chains = Vec::new();
        let mut contact_params = Vec::new();
        for (i, contact) in self.contacts.iter().enumerate() {
            let key = format!("contacts[{i}]");
            contact_chains.push(chain(&mesh, &contact.group, &format!("{key}.group"), &mut c).unwrap_or_default());
            contact_params.push(contact_friction(friction, contact.friction.as_ref(), &key, &mut c));
        }
        if !c.violations.is_empty() {
            return Ok(c.violations);
        }
        let loaded = LoadedMesh {
            path,
            digest,
            mesh,
            cell_material,
            boundary_nodes,
            boundary_chains: boundary_chains.into_iter().collect(),
            contact_chains,
            contact_params: contact_params.into_iter().map(|p| p.expect("checked above")).collect(),
            equilibrium: None,
        };
        let mut loaded = loaded;
        self.check_contacts(&loaded, &mut c);
        if let Err(e) = crate::fem::assembly::check(&self.definition(&loaded)) {
            c.fail("boundaries", "[...]", e.0);
        }
        if c.violations.is_empty() && self.gravity.is_some() {
            loaded.equilibrium = self.settle(&loaded, &mut c);
        }
        self.loaded = Some(Arc::new(loaded));
        Ok(c.violations)
    }

    /// The static equilibrium under gravity ([`crate::fem::equilibrium`]), refused where the
    /// body is not held, where a contact point would have to carry more than its static
    /// strength `μ_k (1/R*₀) f_n` to start stuck, or where an evolving contact would start in
    /// tension or with a gap closed.
    fn settle(&self, loaded: &LoadedMesh, c: &mut Checker<'_>) -> Option<Equilibrium> {
        let g = self.gravity.unwrap_or_default();
        let value = format!("[{}, {}]", shortest(g[0]), shortest(g[1]));
        let assembled = match crate::fem::assemble(&self.definition(loaded)) {
            Ok(assembled) => assembled,
            Err(e) => {
                c.fail("boundaries", "[...]", e.0);
                return None;
            }
        };
        let equilibrium = match under_gravity(&assembled)? {
            Ok(equilibrium) => equilibrium,
            Err(e) => {
                c.fail("gravity", value.as_str(), e);
                return None;
            }
        };
        let contact = &assembled.contact;
        for (k, point) in contact.points.iter().enumerate() {
            let params = contact.params(k);
            let f_n = initial_normal_traction(contact, &equilibrium, k);
            if contact.evolves(k) {
                let name = &self.contacts[point.surface].group;
                let closing =
                    contact.gap[k] > 0.0 && contact.gap[k] + point.normal.apply(&equilibrium.displacement) < 0.0;
                if (contact.gap[k] <= 0.0 && f_n <= 0.0) || closing {
                    let rule = format!(
                        "m/s² {} the evolving contact {name:?} at a contact point where its normal traction would be \
                         {:.1} Pa: the body at rest under its weight must press every point it starts touching and \
                         leave every gap open; press the contact (its normal_traction) or hold the body by a boundary",
                        if closing { "closes a gap of" } else { "lifts the body off" },
                        f_n
                    );
                    c.fail("gravity", value.as_str(), rule);
                    return None;
                }
            }
            let strength = params.mu_k * params.initial_structure() * f_n;
            let f_t = equilibrium.traction_t[k] + params.f0 * point.loading_direction;
            if f_n > 0.0 && f_t.abs() > strength {
                let name = &self.contacts[point.surface].group;
                let rule = format!(
                    "m/s² loads contact {name:?} beyond its static strength before anything moves: the body at \
                     rest on it needs |f_t| = {:.1} Pa at a contact point where mu_k (1/R*) f_n = {:.1} Pa (f_n = \
                     {:.1} Pa); raise the contact's normal traction or its friction, or hold the body by a boundary",
                    f_t.abs(),
                    strength,
                    f_n
                );
                c.fail("gravity", value.as_str(), rule);
                return None;
            }
        }
        Some(equilibrium)
    }

    /// Each cell's material: every cell in exactly one material group.
    fn cell_materials(&self, mesh: &Mesh, c: &mut Checker<'_>) -> Vec<usize> {
        let mut material = vec![usize::MAX; mesh.cells.len()];
        let mut default = None;
        for (i, m) in self.materials.iter().enumerate() {
            let key = format!("materials[{i}].group");
            let Some(name) = &m.group else {
                match default {
                    Some(first) => c.fail(
                        &key,
                        "none",
                        format!(
                            "is left out by materials[{first}] already: one material may take the cells no other names"
                        ),
                    ),
                    None => default = Some(i),
                }
                continue;
            };
            let Some(Members::Cells(cells)) = group(mesh, name, &key, "surface", c) else { continue };
            for &cell in cells {
                if material[cell] != usize::MAX {
                    let other = self.materials[material[cell]].group.as_deref().unwrap_or("");
                    let at = centre(mesh, cell);
                    let rule = format!("shares the cell at {at} with {other:?}: a cell takes one material");
                    c.fail(&key, format!("{name:?}"), rule);
                    return material;
                }
                material[cell] = i;
            }
        }
        let missing: Vec<usize> = (0..mesh.cells.len()).filter(|&k| material[k] == usize::MAX).collect();
        match (default, missing.first()) {
            (Some(i), _) => missing.iter().for_each(|&k| material[k] = i),
            (None, Some(&first)) => {
                let named: Vec<String> =
                    self.materials.iter().map(|m| format!("{:?}", m.group.as_deref().unwrap_or(""))).collect();
                let rule = format!(
                    "leave {} cells without a material (the first at {}): name a material for every surface group, \
                     or leave one material's group out to give it the rest; the mesh has {}",
                    missing.len(),
                    centre(mesh, first),
                    describe_groups(mesh)
                );
                c.fail("materials", format!("[{}]", named.join(", ")), rule);
            }
            (None, None) => {}
        }
        material
    }

    /// The normal traction of each contact: defined, finite and not negative at every Gauss
    /// point, a table covering the contact; and `f0` inside the initial subloading surface.
    fn check_contacts(&self, loaded: &LoadedMesh, c: &mut Checker<'_>) {
        for (i, (contact, chain)) in self.contacts.iter().zip(&loaded.contact_chains).enumerate() {
            let key = format!("contacts[{i}].normal_traction");
            let points: Vec<CurvePoint> = segments(chain, &loaded.mesh.nodes)
                .iter()
                .flat_map(|s| s.gauss_points(&loaded.mesh.nodes).map(|g| g.position))
                .collect();
            let gap_key = format!("contacts[{i}].gap");
            let gap_covers = contact.gap.as_ref().is_none_or(|gap| covers_contact(gap, &points, &gap_key, c));
            if !covers_contact(&contact.normal_traction, &points, &key, c) || !gap_covers {
                continue;
            }
            let values: Vec<f64> = points.iter().map(|p| contact.normal_traction.at(*p)).collect();
            if let Some((p, v)) = points.iter().zip(&values).find(|(_, v)| !(v.is_finite() && **v >= 0.0)) {
                c.fail(&key, format!("{} Pa", shortest(*v)), format!("at the contact point ({}, {}) (arc length {} m): a normal traction must be finite and not negative", shortest(p.x), shortest(p.y), shortest(p.arc)));
                continue;
            }
            if let Some(gap) = &contact.gap {
                let gaps: Vec<(&CurvePoint, f64, f64)> =
                    points.iter().zip(&values).map(|(p, v)| (p, gap.at(*p), *v)).collect();
                if let Some((p, g, _)) = gaps.iter().find(|(_, g, _)| !(g.is_finite() && *g >= 0.0)) {
                    c.fail(
                        &format!("contacts[{i}].gap"),
                        format!("{} m", shortest(*g)),
                        format!(
                            "at the contact point ({}, {}): a gap must be finite and not negative",
                            shortest(p.x),
                            shortest(p.y)
                        ),
                    );
                    continue;
                }
                if let Some((p, g, v)) = gaps.iter().find(|(_, g, v)| *g > 0.0 && *v > 0.0) {
                    c.fail(&format!("contacts[{i}].gap"), format!("{} m", shortest(*g)), format!("at the contact point ({}, {}), where the normal traction is {} Pa: a point is pressed (gap 0) or open (normal traction 0), not both", shortest(p.x), shortest(p.y), shortest(*v)));
                    continue;
                }
            }
            let params = &loaded.contact_params[i];
            let weakest = values.iter().copied().filter(|v| *v > 0.0).fold(f64::INFINITY, f64::min);
            let strength = params.mu_k * params.initial_structure() * weakest;
            if weakest.is_finite() && params.f0 > strength {
                c.fail(&format!("contacts[{i}].friction.f0"), params.f0, format!("must not exceed the initial strength mu_k (1/R*) f_n = {} Pa of the contact's weakest loaded point (f_n = {} Pa)", shortest(strength), shortest(weakest)));
            }
        }
    }

    /// The body the case describes, for [`crate::fem::assemble`].
    pub fn definition<'a>(&'a self, loaded: &'a LoadedMesh) -> BodyDefinition<'a> {
        let constraints = self.boundaries.iter().zip(&loaded.boundary_nodes).filter_map(|(b, nodes)| {
            let (components, motion) = b.constraint()?;
            Some(Constraint { name: b.group.clone(), nodes: nodes.clone(), components, motion })
        });
        let tractions = self.boundaries.iter().zip(&loaded.boundary_chains).filter_map(|(b, chain)| {
            let traction = match (b.traction, b.pressure) {
                (Some(t), _) => Traction::Vector(t),
                (None, Some(p)) => Traction::Pressure(p),
                (None, None) => return None,
            };
            Some(TractionLoad { chain: chain.clone()?, traction, ramp: b.ramp_time, duration: b.duration })
        });
        let contacts = self.contacts.iter().zip(&loaded.contact_chains).zip(&loaded.contact_params).map(
            |((contact, chain), params)| ContactDefinition {
                name: contact.group.clone(),
                chain: chain.clone(),
                params: params.clone(),
                main_body: contact.main_body(),
                normal_traction: Box::new(move |p: CurvePoint| contact.normal_traction.at(p)),
                normal: contact.normal,
                gap: contact
                    .gap
                    .as_ref()
                    .map(|gap| Box::new(move |p: CurvePoint| gap.at(p)) as Box<dyn Fn(CurvePoint) -> f64>),
            },
        );
        BodyDefinition {
            mesh: &loaded.mesh,
            materials: loaded.cell_material.iter().map(|&m| self.materials[m].material()).collect(),
            constraints: constraints.collect(),
            tractions: tractions.collect(),
            contacts: contacts.collect(),
            axisymmetric: self.axisymmetric,
            gravity: self.gravity,
        }
    }

    /// The fastest prescribed velocity of a boundary or a main body (m/s).
    pub fn driving_velocity(&self) -> f64 {
        let boundaries = self.boundaries.iter().filter_map(|b| b.constraint()).map(|(_, m)| m.largest_speed());
        let contacts = self.contacts.iter().map(|c| c.main_body().motion.largest_speed());
        boundaries.chain(contacts).fold(0.0, f64::max)
    }

    /// Degrees of freedom of the mesh's nodes (before any is fixed); `None` before loading.
    pub fn unknowns(&self) -> Option<usize> {
        self.loaded.as_ref().map(|l| 2 * l.mesh.nodes.len())
    }

    /// An upper bound on the highest angular frequency of the body with its contacts' elastic
    /// springs (rad/s; [`crate::fem::stiffest`]): `α_t` along every contact segment and `α_n`
    /// across it (held or evolving, the normal springs are in the operator). `None` before the
    /// mesh is loaded, and for an
    /// axisymmetric body (its cells' hoop stiffness is not bounded here).
    pub fn stiffest_frequency(&self) -> Option<f64> {
        let loaded = self.loaded.as_ref()?;
        if self.axisymmetric {
            return None;
        }
        let mesh = &loaded.mesh;
        let position = |node: usize| nalgebra::Vector2::new(mesh.nodes[node][0], mesh.nodes[node][1]);
        // Each edge's cell and its corners' places in the cell.
        let mut edges = std::collections::HashMap::new();
        for (c, cell) in mesh.cells.iter().enumerate() {
            let nodes = cell.nodes();
            for i in 0..nodes.len() {
                let j = (i + 1) % nodes.len();
                edges.insert((nodes[i].min(nodes[j]), nodes[i].max(nodes[j])), (c, i, j));
            }
        }
        let mut springs = vec![Vec::new(); mesh.cells.len()];
        for (chain, params) in loaded.contact_chains.iter().zip(&loaded.contact_params) {
            for pair in chain.windows(2) {
                let (a, b) = (pair[0], pair[1]);
                let Some(&(c, i, j)) = edges.get(&(a.min(b), a.max(b))) else { continue };
                let nodes = if mesh.cells[c].nodes()[i] == a { [i, j] } else { [j, i] };
                let tangent = (position(b) - position(a)).normalize();
                let normal = nalgebra::Vector2::new(-tangent.y, tangent.x);
                springs[c].push(EdgeSpring { nodes, direction: tangent, modulus: params.alpha_t });
                springs[c].push(EdgeSpring { nodes, direction: normal, modulus: params.alpha_n });
            }
        }
        let frequency = |c: usize| {
            let material = &self.materials[loaded.cell_material[c]];
            let elasticity =
                PlaneStrain { youngs_modulus: material.youngs_modulus, poisson_ratio: material.poisson_ratio };
            let coords: Vec<_> = mesh.cells[c].nodes().iter().map(|&n| position(n)).collect();
            cell_frequency(&coords, &elasticity, material.density, &springs[c])
        };
        Some(largest((0..mesh.cells.len()).map(frequency)))
    }

    /// Segments and nodes of the contacts, together.
    pub fn contact_sizes(&self) -> (usize, usize) {
        self.loaded.as_ref().map_or((0, 0), |l| {
            let segments: usize = l.contact_chains.iter().map(|c| c.len().saturating_sub(1)).sum();
            (l.contact_chains.iter().map(Vec::len).sum(), segments)
        })
    }
}

/// An axisymmetric mesh lies in the half-plane `r = x ≥ 0`: a node at `x < 0` would put the
/// body across its own axis.
fn check_half_plane(mesh: &Mesh, c: &mut Checker<'_>) {
    if let Some(i) = (0..mesh.nodes.len()).find(|&i| mesh.nodes[i][0] < 0.0) {
        let [x, y] = mesh.nodes[i];
        let rule = format!(
            "needs every node at r = x >= 0: the mesh crosses the axis x = 0 ({} at ({}, {})); an axisymmetric \
             body is meshed in the half-plane x >= 0, its axis along y",
            mesh.node_label(i),
            shortest(x),
            shortest(y)
        );
        c.fail("axisymmetric", "true", rule);
    }
}

/// `name`'s members if it is a group of `kind` ("surface", "curve"); else a violation at `key`
/// listing the groups the mesh has.
fn group<'m>(mesh: &'m Mesh, name: &str, key: &str, kind: &str, c: &mut Checker<'_>) -> Option<&'m Members> {
    let Some(found) = mesh.groups.iter().find(|g| g.name == name) else {
        c.fail(key, format!("{name:?}"), format!("names no group of the mesh; it has {}", describe_groups(mesh)));
        return None;
    };
    let fits = matches!(
        (&found.members, kind),
        (Members::Cells(_), "surface") | (Members::Lines(_), "curve") | (Members::Points(_), "curve")
    );
    if !fits {
        c.fail(
            key,
            format!("{name:?}"),
            format!(
                "is a {} group; a {kind} group is needed here (the mesh has {})",
                group_kind(&found.members),
                describe_groups(mesh)
            ),
        );
        return None;
    }
    Some(&found.members)
}

/// The nodes of a curve or point group.
fn nodes_of(mesh: &Mesh, name: &str, key: &str, c: &mut Checker<'_>) -> Vec<usize> {
    let mut nodes: Vec<usize> = match group(mesh, name, key, "curve", c) {
        Some(Members::Lines(lines)) => lines.iter().flatten().copied().collect(),
        Some(Members::Points(points)) => points.clone(),
        _ => Vec::new(),
    };
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

/// A curve group as one open chain of boundary edges, the body on its left.
fn chain(mesh: &Mesh, name: &str, key: &str, c: &mut Checker<'_>) -> Option<Vec<usize>> {
    match group(mesh, name, key, "curve", c) {
        Some(Members::Lines(_)) => {}
        Some(_) => {
            let rule = "is a point group; a contact or a loaded boundary is a curve group (its line elements)";
            c.fail(key, format!("{name:?}"), rule);
            return None;
        }
        None => return None,
    }
    match mesh.boundary_chain(name) {
        Ok(chain) => Some(chain),
        Err(e) => {
            c.fail(key, format!("{name:?}"), format!("is not one open chain of boundary edges: {e}"));
            None
        }
    }
}

/// Contact point `k`'s normal traction at the start: the prescribed one, and on an evolving
/// contact also the share of the weight its normal spring carries in `equilibrium`.
pub fn initial_normal_traction(contact: &crate::dynamics::ContactBoundary, equilibrium: &Equilibrium, k: usize) -> f64 {
    if contact.evolves(k) && contact.gap[k] <= 0.0 {
        contact.traction_n[k] + equilibrium.traction_n[k]
    } else {
        contact.traction_n[k]
    }
}

/// `[friction]` with a contact's own values over it, read and checked like `[friction]`.
fn contact_friction(
    base: &toml::Table,
    own: Option<&toml::Table>,
    key: &str,
    c: &mut Checker<'_>,
) -> Option<FrictionParams> {
    let mut merged = base.clone();
    for (k, v) in own.into_iter().flatten() {
        merged.insert(k.clone(), v.clone());
    }
    let params: FrictionParams = match toml::Value::Table(merged).try_into() {
        Ok(params) => params,
        Err(e) => {
            c.fail(&format!("{key}.friction"), "{...}", format!("is not a friction table: {}", e.to_string().trim()));
            return None;
        }
    };
    let prefix = c.key(&format!("{key}.friction"));
    let mut inner = Checker::new(&prefix);
    params.check(&mut inner);
    let valid = inner.violations.is_empty();
    c.absorb(inner);
    valid.then_some(params)
}

fn group_kind(members: &Members) -> &'static str {
    match members {
        Members::Cells(_) => "surface",
        Members::Lines(_) => "curve",
        Members::Points(_) => "point",
    }
}

/// "body (surface), bottom (curve), …".
fn describe_groups(mesh: &Mesh) -> String {
    if mesh.groups.is_empty() {
        return "no physical groups (define them in Gmsh with Physical Surface/Curve)".into();
    }
    mesh.groups.iter().map(|g| format!("{:?} ({})", g.name, group_kind(&g.members))).collect::<Vec<_>>().join(", ")
}

/// "(x, y)" of a cell's centroid.
fn centre(mesh: &Mesh, cell: usize) -> String {
    let nodes = mesh.cells[cell].nodes();
    let mean = |k: usize| nodes.iter().map(|&n| mesh.nodes[n][k]).sum::<f64>() / nodes.len() as f64;
    format!("({}, {})", shortest(mean(0)), shortest(mean(1)))
}

/// Whether `profile` gives a value at every one of a contact's `points`: a table must cover
/// them (it does not extrapolate); where it does not, fails `key.at` and says where they lie.
fn covers_contact(profile: &ProfileSpec, points: &[CurvePoint], key: &str, c: &mut Checker<'_>) -> bool {
    let Some((along, from, to)) = profile.covers() else { return true };
    let (low, high) =
        points.iter().map(|p| along.of(*p)).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| (a.min(s), b.max(s)));
    if from <= low && to >= high {
        return true;
    }
    c.fail(
        &format!("{key}.at"),
        format!("[{}, …, {}]", shortest(from), shortest(to)),
        format!(
            "must cover the contact, whose Gauss points lie from {} to {} m in {}",
            shortest(low),
            shortest(high),
            format!("{along:?}").to_lowercase()
        ),
    );
    false
}
