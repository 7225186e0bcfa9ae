//! The shape of a case file. All quantities SI: Pa, m, s, kg.

use serde::Deserialize;

use crate::case::mesh::MeshSpec;
use crate::case::profile;
use crate::dynamics::NormalBehaviour;
use crate::dynamics::method::{ACCURACY_RANGE, Choice, MAX_STEPS, Method};
use crate::fem::PlaneStrain;
use crate::fem::stiffest::{EdgeSpring, cell_frequency, largest};
use crate::frame::Quantity;
use crate::friction::FrictionParams;
use crate::validate::Checker;

/// A whole case.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// The friction law's constants.
    pub friction: FrictionParams,
    /// Time span and integrator.
    pub time: TimeSpec,
    /// What is simulated.
    #[serde(deserialize_with = "scene_spec")]
    pub scene: SceneSpec,
    /// The event catalog.
    #[serde(default)]
    pub events: EventsSpec,
    /// Named nodes and segments (block scenes).
    #[serde(default)]
    pub probes: ProbesSpec,
    /// What the Rerun recording holds.
    #[serde(default)]
    pub record: RecordSpec,
    /// The case as written and overridden, for the recording's properties.
    #[serde(skip)]
    pub source: CaseSource,
}

/// A case as the user gave it: the TOML table after the overrides, and the overrides.
#[derive(Clone, Default)]
pub struct CaseSource {
    pub table: toml::Table,
    pub overrides: Vec<String>,
}

/// Left out of a case's `Debug` form, which names the run ([`crate::record::schema::recording_id`]):
/// every value it holds is in the case's fields already.
impl std::fmt::Debug for CaseSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("..")
    }
}

/// `[time]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    /// Simulated time (s).
    pub t_end: f64,
    /// Time step (s).
    pub dt: f64,
    /// Wilson's θ (-); 1.4 by default, at least 1.37 for unconditional stability.
    #[serde(default = "default_theta")]
    pub theta: f64,
    /// Largest share of the work put in that the integrator may create before the run stops
    /// as too coarse (-); 0.01 by default.
    #[serde(default = "default_energy_tolerance")]
    pub energy_tolerance: f64,
    /// Local error per second of simulated time (1/s) of adaptive stepping by step doubling;
    /// unset (the default): fixed steps of `dt`. When set, `dt` is the first step. See
    /// [`crate::dynamics::step_doubling`]. With the Runge–Kutta methods: their local error per
    /// step ([`crate::dynamics::method`] has their defaults).
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// Largest adaptive step (s); 1000 × `dt` by default ([`DT_MAX_PER_DT`]).
    #[serde(default)]
    pub dt_max: Option<f64>,
    /// The time integrator of dynamic scenes as the case asks for it: `auto` (the default),
    /// resolved for the scene by [`crate::dynamics::method::choose`], or a [`Method`] by name:
    /// Wilson's θ method (the paper's), Tsitouras' 5(4) pair or SDIRK 4(3) on the rate form, or
    /// central differences.
    #[serde(default)]
    pub integrator: Choice,
    /// The relative error of slip-onset times aimed at (-), which sets the method's tolerance
    /// or step ([`Method::for_accuracy`]); unset (the default): the case's `dt` and each
    /// method's default tolerance.
    #[serde(default)]
    pub accuracy: Option<f64>,
    /// The method the run uses: the one named, or `auto`'s choice ([`Case::resolve`](crate::case::Case::resolve)).
    #[serde(skip)]
    pub method: Method,
    /// Why `auto` chose [`Self::method`]; `None` where the case named it.
    #[serde(skip)]
    pub chosen_because: Option<String>,
}

fn default_theta() -> f64 {
    1.4
}

fn default_energy_tolerance() -> f64 {
    0.01
}

impl TimeSpec {
    pub fn check(&self, c: &mut Checker<'_>) {
        c.positive("t_end", self.t_end);
        c.positive("dt", self.dt);
        if c.finite("theta", self.theta) && !(1.37..=3.0).contains(&self.theta) {
            c.fail(
                "theta",
                self.theta,
                "must lie in [1.37, 3] (Wilson's method is unconditionally stable for θ ≥ 1.37)",
            );
        }
        c.positive("energy_tolerance", self.energy_tolerance);
        // Central differences take no tolerance at all: that is the one error worth giving.
        if let Some(tolerance) = self.tolerance {
            match self.method.tolerance_rule() {
                Some(rule) if c.finite("tolerance", tolerance) => {
                    let above = rule.smallest.map_or(tolerance > 0.0, |smallest| tolerance >= smallest);
                    if !(above && tolerance <= rule.largest) {
                        let from = rule.smallest.map_or("(0".to_string(), |smallest| format!("[{smallest:e}"));
                        c.fail("tolerance", tolerance, format!("must lie in {from}, {}] ({})", rule.largest, rule.meaning));
                    }
                }
                Some(_) => {}
                None => c.fail(
                    "tolerance",
                    tolerance,
                    format!(
                        "does not apply to {} = \"{}\", which takes fixed frames of {} sub-stepped to its stability limit",
                        c.key("integrator"),
                        self.method.name(),
                        c.key("dt")
                    ),
                ),
            }
        }
        if let Some(accuracy) = self.accuracy {
            let (smallest, largest) = ACCURACY_RANGE;
            if self.tolerance.is_some() {
                c.fail(
                    "accuracy",
                    accuracy,
                    format!(
                        "sets the tolerance itself: give {} or {}, not both",
                        c.key("accuracy"),
                        c.key("tolerance")
                    ),
                );
            } else if self.method == Method::Cycle {
                c.fail(
                    "accuracy",
                    accuracy,
                    format!(
                        "does not apply to {} = \"cycle\", whose onset errors have no measured map to a setting: \
                         give {} (the change of the contact's state allowed per step) instead",
                        c.key("integrator"),
                        c.key("tolerance")
                    ),
                );
            } else if c.finite("accuracy", accuracy) && !(smallest..=largest).contains(&accuracy) {
                c.fail(
                    "accuracy",
                    accuracy,
                    format!("must lie in [{smallest:e}, {largest:e}] (a relative error of slip-onset times)"),
                );
            }
        }
        if let Some(dt_max) = self.dt_max {
            if self.adaptive_tolerance().is_none() {
                c.fail("dt_max", dt_max, format!("only applies to adaptive stepping: set {} too", c.key("tolerance")));
            } else if c.finite("dt_max", dt_max) && !(dt_max > 0.0 && dt_max <= self.t_end) {
                c.fail("dt_max", dt_max, format!("must lie in (0, {} = {}]", c.key("t_end"), self.t_end));
            }
        }
        if self.t_end.is_finite() && self.dt.is_finite() && self.dt > 0.0 && self.t_end > 0.0 {
            if self.dt > self.t_end {
                c.fail("dt", self.dt, format!("must not exceed {} = {}", c.key("t_end"), self.t_end));
            } else if self.t_end / self.dt > MAX_STEPS && self.method != Method::Cycle {
                // Cycle steps are `dt` only through slips ([`Method::Cycle`]); through stick they grow.
                c.fail(
                    "dt",
                    self.dt,
                    format!(
                        "gives {:.3e} steps for {} = {} s; at most {MAX_STEPS:e} are allowed",
                        self.t_end / self.dt,
                        c.key("t_end"),
                        self.t_end
                    ),
                );
            }
        }
    }

    /// The tolerance of adaptive stepping, if steps are adaptive ([`Method::adaptive_tolerance`]).
    pub fn adaptive_tolerance(&self) -> Option<f64> {
        self.method.adaptive_tolerance(self.tolerance)
    }

    /// The energy guard's share (`energy_tolerance`) where the method keeps an energy ledger
    /// ([`Method::guards_energy`]).
    pub fn energy_guard(&self) -> Option<f64> {
        self.method.guards_energy().then_some(self.energy_tolerance)
    }

    /// Largest adaptive step (s): as given, or [`DT_MAX_PER_DT`] times `dt`. Never derived
    /// from `t_end`, so that no step depends on when the run ends.
    pub fn dt_max(&self) -> f64 {
        self.dt_max.unwrap_or(DT_MAX_PER_DT * self.dt)
    }

    /// Smallest adaptive step (s) ([`Method::dt_min`]).
    pub fn dt_min(&self) -> f64 {
        self.method.dt_min(self.t_end, self.dt)
    }

    /// Number of steps: `t_end/dt` rounded up; the last step is shortened to end at `t_end`.
    pub fn steps(&self) -> u64 {
        (self.t_end / self.dt - 1e-9).ceil().max(1.0) as u64
    }
}

/// The largest adaptive step when `time.dt_max` is not given, in steps of `dt`: 10 s for the
/// paper's dt = 0.01 s. Step doubling needs a bound (it grows Wilson's steps through stick until
/// they miss the dynamics: the paper case at tolerance 1e-5 without one fails at 316 s, in its
/// 31st step); the Runge–Kutta methods' steps stay far below it (SDIRK4's 0.35 s at most on the
/// paper case).
pub const DT_MAX_PER_DT: f64 = 1000.0;

/// Marks an error from inside `[scene]` whose message starts with its own key path, so that
/// the case's error says `scene.nx: ...` (see [`crate::case`]).
pub(crate) const NESTED_KEY: char = '\u{1f}';

/// Reads `[scene]` through its own path tracker: serde's internally tagged enums buffer their
/// content and would report every error inside the table at `scene`, without the key.
fn scene_spec<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<SceneSpec, D::Error> {
    use serde::de::Error;
    let mut table = toml::Table::deserialize(deserializer)?;
    let kind = match table.remove("kind") {
        Some(toml::Value::String(kind)) => kind,
        Some(other) => {
            return Err(D::Error::custom(format!(
                "{NESTED_KEY}kind: invalid type: {}, expected a string",
                other.type_str()
            )));
        }
        None => return Err(D::Error::missing_field("kind")),
    };
    for key in ["gravity", "axisymmetric"] {
        if kind != "mesh" && table.contains_key(key) {
            let why = match kind.as_str() {
                "point" | "spring_block" => "has no body to weigh or revolve",
                _ => "is the paper's plane-strain block, weightless (pose it as a mesh, as cases/paper_mesh.toml does)",
            };
            return Err(D::Error::custom(format!(
                "{NESTED_KEY}{key}: applies to a body drawn as a mesh (kind = \"mesh\"); a {kind} scene {why}"
            )));
        }
    }
    let tracked = |table: toml::Table| {
        fn read<T: serde::de::DeserializeOwned>(table: toml::Table) -> Result<T, String> {
            serde_path_to_error::deserialize(toml::Value::Table(table)).map_err(|e| {
                let path = e.path().to_string();
                let inner = e.into_inner().to_string();
                let inner = inner.trim_end().to_owned();
                if path == "." || path.is_empty() { inner } else { format!("{NESTED_KEY}{path}: {inner}") }
            })
        }
        match kind.as_str() {
            "point" => read(table).map(SceneSpec::Point),
            "spring_block" => read(table).map(SceneSpec::SpringBlock),
            "block" => read(table).map(SceneSpec::Block),
            "mesh" => read(table).map(SceneSpec::Mesh),
            other => Err(format!(
                "{NESTED_KEY}kind: unknown variant `{other}`, expected one of `point`, `spring_block`, `block`, `mesh`"
            )),
        }
    };
    tracked(table).map_err(D::Error::custom)
}

/// `[scene]`, chosen by `kind` (read by [`scene_spec`]).
#[derive(Debug, Clone)]
pub enum SceneSpec {
    /// One contact point under a prescribed relative sliding velocity history.
    Point(PointSpec),
    /// A rigid block on the frictional contact, pulled through a spring.
    SpringBlock(SpringBlockSpec),
    /// The plane-strain elastic block of the paper on the frictional base.
    Block(BlockSpec),
    /// A plane-strain body from a Gmsh mesh, with its materials, boundaries and contacts.
    Mesh(MeshSpec),
}

/// `kind = "point"`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointSpec {
    /// Normal traction `f_n` (Pa): held constant, or its initial value.
    pub normal_traction: f64,
    /// `"held"` (default) or `"evolving"`: `ḟ_n = -α_n v̄_n` under the phases' `normal_velocity`.
    #[serde(default)]
    pub normal: NormalBehaviour,
    /// Relative sliding velocity `v̄_t = v_block - v_base` (m/s) held for `duration` (s), in
    /// order; after the last phase the point is held (`v̄_t = 0`).
    pub phases: Vec<Phase>,
}

/// One phase of a point history.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Phase {
    /// Relative sliding velocity (m/s).
    pub velocity: f64,
    /// Duration (s).
    pub duration: f64,
    /// Relative normal velocity `v̄_n` (m/s, positive opening); only with `normal = "evolving"`.
    #[serde(default)]
    pub normal_velocity: f64,
}

/// `kind = "spring_block"`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringBlockSpec {
    /// Block mass per unit contact area (kg/m²).
    pub mass: f64,
    /// Spring stiffness per unit contact area (Pa/m).
    pub stiffness: f64,
    /// Velocity of the spring's far end (m/s).
    pub velocity: f64,
    /// Normal traction on the contact `σ_n` (Pa).
    pub normal_traction: f64,
}

/// `kind = "block"`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    /// Width `W` (m).
    pub width: f64,
    /// Height `H` (m).
    pub height: f64,
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// Young's modulus `E` (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio `ν` (-).
    pub poisson_ratio: f64,
    /// Density `ρ` (kg/m³).
    pub density: f64,
    /// Velocity of the base along x (m/s).
    pub base_velocity: f64,
    /// Time over which the base accelerates smoothly from rest to `base_velocity` (s); 0 (the
    /// default) starts it impulsively.
    #[serde(default)]
    pub base_ramp_time: f64,
    /// Normal traction on the contact (Pa): held constant, or its initial value.
    pub normal_traction: NormalTractionSpec,
    /// `"held"` (default) or `"evolving"`: whether the normal traction follows `ḟ_n = -α_n v̄_n`.
    #[serde(default)]
    pub normal: NormalBehaviour,
}

/// Normal traction along the contact.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum NormalTractionSpec {
    /// The same everywhere.
    Uniform { value: f64 },
    /// Linear from `left` (x = 0) to `right` (x = W): the paper's triangle.
    Linear { left: f64, right: f64 },
    /// Piecewise linear through `(x[i], value[i])`, `x` increasing from 0 to W.
    Table { x: Vec<f64>, value: Vec<f64> },
}

impl NormalTractionSpec {
    /// The traction at `x` (Pa) on a contact of width `width`.
    pub fn at(&self, x: f64, width: f64) -> f64 {
        match self {
            NormalTractionSpec::Uniform { value } => *value,
            NormalTractionSpec::Linear { left, right } => profile::linear(x, [0.0, width], [*left, *right]),
            NormalTractionSpec::Table { x: xs, value } => profile::table(x, xs, value),
        }
    }

    fn check(&self, width: f64, c: &mut Checker<'_>) {
        match self {
            NormalTractionSpec::Uniform { value } => c.non_negative("normal_traction.value", *value),
            NormalTractionSpec::Linear { left, right } => {
                c.non_negative("normal_traction.left", *left);
                c.non_negative("normal_traction.right", *right);
            }
            NormalTractionSpec::Table { x, value } => {
                if x.len() < 2 || x.len() != value.len() {
                    c.fail(
                        "normal_traction.x",
                        format!("{x:?}"),
                        format!(
                            "must have at least 2 entries, as many as {} ({})",
                            c.key("normal_traction.value"),
                            value.len()
                        ),
                    );
                    return;
                }
                for (i, v) in value.iter().enumerate() {
                    c.non_negative(&format!("normal_traction.value[{i}]"), *v);
                }
                let increasing = x.windows(2).all(|w| w[1] > w[0]);
                if !x.iter().all(|v| v.is_finite()) || !increasing {
                    c.fail("normal_traction.x", format!("{x:?}"), "must be finite and strictly increasing");
                } else if x[0] > 0.0 || x[x.len() - 1] < width {
                    c.fail(
                        "normal_traction.x",
                        format!("{x:?}"),
                        format!("must cover the contact, from 0 to {} = {width} m", c.key("width")),
                    );
                }
            }
        }
    }
}

impl SceneSpec {
    /// Unknowns of the scene's body; `None` for a point scene.
    pub fn unknowns(&self) -> Option<usize> {
        match self {
            SceneSpec::Point(_) => None,
            SceneSpec::SpringBlock(_) => Some(1),
            SceneSpec::Block(b) => {
                Some(b.nx.saturating_add(1).saturating_mul(b.ny.saturating_add(1)).saturating_mul(2))
            }
            SceneSpec::Mesh(m) => Some(m.unknowns().unwrap_or(0)),
        }
    }

    /// An upper bound on the highest angular frequency of the body with its contact's elastic
    /// springs `α_t` and `α_n` (rad/s; [`crate::fem::stiffest`]), for a block or a mesh; `None` for the other
    /// scenes, and for an axisymmetric mesh.
    pub fn stiffest_frequency(&self, friction: &FrictionParams) -> Option<f64> {
        match self {
            SceneSpec::Point(_) | SceneSpec::SpringBlock(_) => None,
            SceneSpec::Block(b) => {
                use nalgebra::Vector2;
                let (hx, hy) = (b.width / b.nx as f64, b.height / b.ny as f64);
                let coords =
                    [Vector2::new(0.0, 0.0), Vector2::new(hx, 0.0), Vector2::new(hx, hy), Vector2::new(0.0, hy)];
                let elasticity = PlaneStrain { youngs_modulus: b.youngs_modulus, poisson_ratio: b.poisson_ratio };
                // The contact runs along the bottom edge of the bottom row of cells.
                let spring = |direction, modulus| EdgeSpring { nodes: [0, 1], direction, modulus };
                let springs = [
                    spring(Vector2::new(1.0, 0.0), friction.alpha_t),
                    spring(Vector2::new(0.0, 1.0), friction.alpha_n),
                ];
                let inside = cell_frequency(&coords, &elasticity, b.density, &[]);
                Some(largest([inside, cell_frequency(&coords, &elasticity, b.density, &springs)]))
            }
            SceneSpec::Mesh(m) => m.stiffest_frequency(),
        }
    }

    pub fn kind(&self) -> &'static str {
        match self {
            SceneSpec::Point(_) => "point",
            SceneSpec::SpringBlock(_) => "spring_block",
            SceneSpec::Block(_) => "block",
            SceneSpec::Mesh(_) => "mesh",
        }
    }

    /// Contact-surface nodes and segments (the probes' and the selections' ranges).
    pub fn contact_sizes(&self) -> (usize, usize) {
        match self {
            SceneSpec::Block(b) => (b.nx + 1, b.nx),
            SceneSpec::Mesh(m) => m.contact_sizes(),
            _ => (0, 1),
        }
    }

    /// The smallest positive normal traction (Pa) at a contact point, and the key that sets
    /// it; `None` where no point is loaded.
    pub fn weakest_normal_traction(&self) -> Option<(f64, &'static str)> {
        let (f_n, key) = match self {
            SceneSpec::Point(p) => (p.normal_traction, "scene.normal_traction"),
            SceneSpec::SpringBlock(s) => (s.normal_traction, "scene.normal_traction"),
            SceneSpec::Block(b) => {
                use crate::fem::curve::{gauss_shapes, interpolate};
                let dx = b.width / b.nx as f64;
                let weakest = (0..b.nx)
                    .flat_map(|k| gauss_shapes().map(|shape| interpolate(k as f64 * dx, (k + 1) as f64 * dx, shape)))
                    .map(|x| b.normal_traction.at(x, b.width))
                    .filter(|f| *f > 0.0)
                    .fold(f64::INFINITY, f64::min);
                (weakest, "scene.normal_traction")
            }
            // Each contact's own f0 is checked where the mesh is loaded.
            SceneSpec::Mesh(_) => return None,
        };
        (f_n > 0.0 && f_n.is_finite()).then_some((f_n, key))
    }

    /// The velocity that drives the scene (m/s): 10 × this is the default event threshold.
    pub fn driving_velocity(&self) -> f64 {
        let v = match self {
            SceneSpec::Point(p) => p.phases.iter().fold(0.0_f64, |m, ph| m.max(ph.velocity.abs())),
            SceneSpec::SpringBlock(s) => s.velocity.abs(),
            SceneSpec::Block(b) => b.base_velocity.abs(),
            SceneSpec::Mesh(m) => m.driving_velocity(),
        };
        if v > 0.0 && v.is_finite() { v } else { 1e-3 }
    }

    /// Whether some contact's normal traction evolves (`normal = "evolving"`).
    pub fn has_evolving_normal(&self) -> bool {
        self.evolving_contacts().into_iter().any(|e| e)
    }

    /// Whether each contact's normal traction evolves, in the order of the scene's contacts.
    pub fn evolving_contacts(&self) -> Vec<bool> {
        let evolving = |n: &NormalBehaviour| *n == NormalBehaviour::Evolving;
        match self {
            SceneSpec::Point(p) => vec![evolving(&p.normal)],
            SceneSpec::SpringBlock(_) => vec![false],
            SceneSpec::Block(b) => vec![evolving(&b.normal)],
            SceneSpec::Mesh(m) => m.contacts.iter().map(|c| evolving(&c.normal)).collect(),
        }
    }

    pub fn check(&self, c: &mut Checker<'_>) {
        match self {
            SceneSpec::Point(p) => {
                c.non_negative("normal_traction", p.normal_traction);
                if p.phases.is_empty() {
                    c.fail("phases", "[]", "must list at least one {velocity, duration} phase");
                }
                for (i, phase) in p.phases.iter().enumerate() {
                    c.finite(&format!("phases[{i}].velocity"), phase.velocity);
                    c.positive(&format!("phases[{i}].duration"), phase.duration);
                    let key = format!("phases[{i}].normal_velocity");
                    if c.finite(&key, phase.normal_velocity)
                        && phase.normal_velocity != 0.0
                        && p.normal != NormalBehaviour::Evolving
                    {
                        let rule =
                            format!("needs {} = \"evolving\": a held normal traction does not move", c.key("normal"));
                        c.fail(&key, phase.normal_velocity, rule);
                    }
                }
            }
            SceneSpec::SpringBlock(s) => {
                c.positive("mass", s.mass);
                c.positive("stiffness", s.stiffness);
                c.finite("velocity", s.velocity);
                c.non_negative("normal_traction", s.normal_traction);
            }
            SceneSpec::Block(b) => {
                c.positive("width", b.width);
                c.positive("height", b.height);
                if b.nx == 0 {
                    c.fail("nx", b.nx, "must be at least 1");
                }
                if b.ny == 0 {
                    c.fail("ny", b.ny, "must be at least 1");
                }
                c.positive("youngs_modulus", b.youngs_modulus);
                if c.finite("poisson_ratio", b.poisson_ratio) && !(0.0..0.5).contains(&b.poisson_ratio) {
                    c.fail("poisson_ratio", b.poisson_ratio, "must lie in [0, 0.5)");
                }
                c.positive("density", b.density);
                c.finite("base_velocity", b.base_velocity);
                c.non_negative("base_ramp_time", b.base_ramp_time);
                b.normal_traction.check(b.width, c);
            }
            SceneSpec::Mesh(m) => m.check(c),
        }
    }
}

/// `[events]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EventsSpec {
    /// A segment slips while its plastic slip rate exceeds this (m/s); default 10 × the
    /// driving velocity.
    pub slip_rate_threshold: Option<f64>,
    /// A segment's event starting less than this after its previous one ended continues it (s);
    /// default 0: every threshold crossing is an event.
    #[serde(default)]
    pub merge_within: f64,
}

/// `[probes]`: names for nodes and segments of a body's contacts, so that figures and
/// recordings can say "Node 1" or "Segment A" as the paper does.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbesSpec {
    /// Contact-surface nodes, numbered from 0 along each contact, contact after contact.
    #[serde(default)]
    pub nodes: Vec<Probe>,
    /// Contact segments (element edges), numbered the same way.
    #[serde(default)]
    pub segments: Vec<Probe>,
}

/// One named probe: by its number, or by position (the node, or the segment whose centre,
/// lies nearest; the first of equals).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Probe {
    pub name: String,
    /// Its number along the contacts.
    pub index: Option<usize>,
    /// Its x (m): the one whose x is nearest.
    pub x: Option<f64>,
    /// A point `[x, y]` (m): the one nearest to it.
    pub at: Option<[f64; 2]>,
}

impl Probe {
    /// The probe's index among nodes or segments at `positions`.
    pub fn resolve(&self, positions: &[[f64; 2]]) -> usize {
        let nearest = |distance: &dyn Fn(&[f64; 2]) -> f64| {
            (0..positions.len())
                .min_by(|&a, &b| distance(&positions[a]).total_cmp(&distance(&positions[b])))
                .unwrap_or(0)
        };
        match (self.index, self.x, self.at) {
            (Some(index), _, _) => index,
            (None, Some(x), _) => nearest(&|p| (p[0] - x).abs()),
            (None, None, Some([x, y])) => nearest(&|p| (p[0] - x).hypot(p[1] - y)),
            (None, None, None) => 0,
        }
    }
}

impl ProbesSpec {
    pub fn check(&self, scene: &SceneSpec, c: &mut Checker<'_>) {
        let (nodes, segments) = scene.contact_sizes();
        for (list, key, count) in [(&self.nodes, "nodes", nodes), (&self.segments, "segments", segments)] {
            for (i, probe) in list.iter().enumerate() {
                let forms = [probe.index.is_some(), probe.x.is_some(), probe.at.is_some()];
                if forms.iter().filter(|&&f| f).count() != 1 {
                    c.fail(
                        &format!("{key}[{i}]"),
                        format!("{:?}", probe.name),
                        "must give exactly one of index (its number), x (m) or at ([x, y] in m)",
                    );
                }
                if count == 0 {
                    c.fail(
                        &format!("{key}[{i}]"),
                        format!("{:?}", probe.name),
                        format!("is not allowed: a {} scene has no nodes", scene.kind()),
                    );
                }
                if let Some(index) = probe.index.filter(|&index| count > 0 && index >= count) {
                    let rule = format!(
                        "must be below {count} (the scene has {count} {key}, numbered from 0 along its contacts)"
                    );
                    c.fail(&format!("{key}[{i}].index"), index, rule);
                }
                if let Some(x) = probe.x {
                    c.finite(&format!("{key}[{i}].x"), x);
                }
                if let Some(at) = probe.at {
                    c.finite(&format!("{key}[{i}].at[0]"), at[0]);
                    c.finite(&format!("{key}[{i}].at[1]"), at[1]);
                }
                if probe.name.trim().is_empty() {
                    c.fail(&format!("{key}[{i}].name"), format!("{:?}", probe.name), "must not be empty");
                }
            }
        }
    }
}

/// `[record]`: what goes into the recording.
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct RecordSpec {
    /// Per-segment quantities (default all): `traction_t`, `traction_n`, `R`, `R_star`,
    /// `structure`, `slip_rate`, `slip`.
    #[serde(default = "all_quantities")]
    pub quantities: Vec<Quantity>,
    /// Segments with time series: `"all"`, `"probes"` or a list of indices. Default: all while
    /// the scene has at most 64 segments, else the probes.
    #[serde(default)]
    pub segments: Selection,
    /// Contact-surface nodes with `u_x`, `u_y` series, chosen the same way.
    #[serde(default)]
    pub nodes: Selection,
    /// While no segment slips, record every `stick_every`-th step (default 50); every step
    /// while any segment slips.
    #[serde(default = "default_stick_every")]
    pub stick_every: u64,
    /// While a segment slips, record every `slip_every`-th step (default 1: every step), and
    /// always the steps where the contact goes from stick to slip and back.
    #[serde(default = "default_slip_every")]
    pub slip_every: u64,
    /// Displacement magnification of the spatial view (default 1: true scale).
    #[serde(default = "default_magnification")]
    pub magnification: f64,
    /// Log the spatial and space-time views (default true).
    #[serde(default = "default_spatial")]
    pub spatial: bool,
}

impl Default for RecordSpec {
    fn default() -> Self {
        Self {
            quantities: all_quantities(),
            segments: Selection::default(),
            nodes: Selection::default(),
            stick_every: default_stick_every(),
            slip_every: default_slip_every(),
            magnification: default_magnification(),
            spatial: default_spatial(),
        }
    }
}

fn all_quantities() -> Vec<Quantity> {
    Quantity::ALL.to_vec()
}

fn default_stick_every() -> u64 {
    50
}

fn default_slip_every() -> u64 {
    1
}

fn default_magnification() -> f64 {
    1.0
}

fn default_spatial() -> bool {
    true
}

/// Which segments or nodes get time series.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(untagged)]
pub enum Selection {
    /// `"all"`, `"probes"` or `"auto"` (the default).
    Named(SelectionName),
    /// Explicit indices from the left.
    Indices(Vec<usize>),
}

/// The forms a selection takes, for error messages.
const SELECTION_FORMS: &str = "\"all\", \"probes\", \"auto\" or a list of indices such as [0, 4, 9]";

/// Read by hand: serde's untagged enums answer a wrong value with "data did not match any
/// variant of untagged enum Selection", without saying what is allowed.
impl<'de> Deserialize<'de> for Selection {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Forms;
        impl<'de> serde::de::Visitor<'de> for Forms {
            type Value = Selection;

            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(SELECTION_FORMS)
            }

            fn visit_str<E: serde::de::Error>(self, value: &str) -> Result<Selection, E> {
                match value {
                    "all" => Ok(Selection::Named(SelectionName::All)),
                    "probes" => Ok(Selection::Named(SelectionName::Probes)),
                    "auto" => Ok(Selection::Named(SelectionName::Auto)),
                    other => Err(E::custom(format!("unknown selection \"{other}\", expected {SELECTION_FORMS}"))),
                }
            }

            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Selection, A::Error> {
                let mut indices = Vec::new();
                while let Some(index) = seq.next_element::<usize>()? {
                    indices.push(index);
                }
                Ok(Selection::Indices(indices))
            }
        }
        deserializer.deserialize_any(Forms)
    }
}

impl Default for Selection {
    fn default() -> Self {
        Selection::Named(SelectionName::Auto)
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SelectionName {
    All,
    Probes,
    Auto,
}

/// Above this many segments, only probes get time series by default.
pub const MAX_DEFAULT_SEGMENTS: usize = 64;

impl Selection {
    /// Indices out of `count`, with `probes` the named ones.
    pub fn resolve(&self, count: usize, probes: &[usize]) -> Vec<usize> {
        let auto = || if count <= MAX_DEFAULT_SEGMENTS + 1 { (0..count).collect() } else { probes.to_vec() };
        match self {
            Selection::Named(SelectionName::Auto) => auto(),
            Selection::Named(SelectionName::All) => (0..count).collect(),
            Selection::Named(SelectionName::Probes) => probes.to_vec(),
            Selection::Indices(list) => list.clone(),
        }
    }
}

impl RecordSpec {
    pub fn check(&self, scene: &SceneSpec, c: &mut Checker<'_>) {
        if self.stick_every == 0 {
            c.fail("stick_every", 0, "must be at least 1");
        }
        if self.slip_every == 0 {
            c.fail("slip_every", 0, "must be at least 1");
        }
        c.positive("magnification", self.magnification);
        let (nodes, segments) = scene.contact_sizes();
        for (i, quantity) in self.quantities.iter().enumerate() {
            if let Some(first) = self.quantities[..i].iter().position(|q| q == quantity) {
                c.fail(
                    &format!("quantities[{i}]"),
                    format!("\"{}\"", quantity.name()),
                    format!("repeats quantities[{first}]: list each quantity once"),
                );
            }
        }
        for (selection, key, count) in [(&self.segments, "segments", segments), (&self.nodes, "nodes", nodes)] {
            if let Selection::Indices(list) = selection {
                for (i, &index) in list.iter().enumerate() {
                    if let Some(first) = list[..i].iter().position(|&j| j == index) {
                        c.fail(&format!("{key}[{i}]"), index, format!("repeats {key}[{first}]: list each index once"));
                    }
                    if index >= count {
                        let rule = if count == 0 {
                            format!("is not allowed: a {} scene has no nodes", scene.kind())
                        } else {
                            format!(
                                "must be below {count} (the scene has {count} {key}, numbered from 0 along its contacts)"
                            )
                        };
                        c.fail(&format!("{key}[{i}]"), index, rule);
                    }
                }
            }
        }
    }
}
