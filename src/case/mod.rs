//! Case files: TOML, SI units, unknown keys rejected, every rule checked before a run starts.
//!
//! A case is read into a TOML table, `--set KEY=VALUE` overrides are applied to that table, and
//! only then is it deserialized and validated, so overrides pass through exactly the same
//! checks as the file.

pub mod error;
pub mod mesh;
pub mod overrides;
pub mod profile;
pub mod spec;
pub mod units;

use std::fmt;
use std::path::Path;

pub use spec::*;

pub use crate::case::error::CaseError;
use crate::dynamics::Stepping;
use crate::dynamics::method::{AUTO_PAIR_UNKNOWNS, Choice, MAX_STEPS, Problem, choose};
use crate::validate::{Checker, Violation, shortest};

/// Reads, overrides, parses and validates a case file.
pub fn load(path: &Path, overrides: &[String]) -> Result<Case, CaseError> {
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    from_str_at(&read(path)?, overrides, dir)
}

/// The text of a case file, refused unless it is a regular file of at most [`MAX_CASE_BYTES`]
/// ([`crate::files`]): `/dev/zero`, a named pipe or a stray data file is refused, not read until
/// memory runs out or for ever.
pub fn read(path: &Path) -> Result<String, CaseError> {
    crate::files::read_text_capped(path, MAX_CASE_BYTES, "a case file is a few kilobytes of TOML")
        .map_err(|e| CaseError::Io { path: path.display().to_string(), message: e.reason })
}

/// The largest case file read (bytes). The shipped cases are under 5 kB; a probe list of every
/// node of a 10 000-element mesh is under 1 MiB.
pub const MAX_CASE_BYTES: u64 = 4 << 20;

/// As [`load`], from text, with the files it names (a mesh) relative to the working folder.
pub fn from_str(text: &str, overrides: &[String]) -> Result<Case, CaseError> {
    from_str_at(text, overrides, Path::new("."))
}

/// As [`load`], from text, with the files it names relative to `dir`.
pub fn from_str_at(text: &str, overrides: &[String], dir: &Path) -> Result<Case, CaseError> {
    let mut table: toml::Table = text.parse().map_err(|e: toml::de::Error| CaseError::Parse(e.to_string()))?;
    for item in overrides {
        overrides::apply(&mut table, item)?;
    }
    let case: Case = if overrides.is_empty() {
        // Deserializing the text keeps line and column in the error message.
        deserialize(toml::Deserializer::parse(text).map_err(|e| CaseError::Parse(e.to_string()))?)?
    } else {
        deserialize(table.clone())?
    };
    let mut case = case;
    case.source = spec::CaseSource { table, overrides: overrides.to_vec() };
    case.load_files(dir)?;
    case.resolve();
    let mut violations = case.violations();
    if violations.is_empty() {
        violations.extend(case.apply_accuracy());
    }
    if violations.is_empty() { Ok(case) } else { Err(CaseError::Invalid(violations)) }
}

fn deserialize<'de, D>(deserializer: D) -> Result<Case, CaseError>
where
    D: serde::Deserializer<'de>,
    D::Error: fmt::Display,
{
    serde_path_to_error::deserialize(deserializer).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner().to_string();
        // toml appends "in `key`" lines that repeat the path given in front.
        let inner: Vec<&str> = inner.trim_end().lines().filter(|l| !l.starts_with("in `")).collect();
        let inner = inner.join("\n");
        if path == "." || path.is_empty() {
            CaseError::Parse(format!("case: {inner}"))
        } else if let Some(nested) = inner.strip_prefix(spec::NESTED_KEY) {
            CaseError::Parse(format!("{path}.{nested}"))
        } else {
            CaseError::Parse(format!("{path}: {inner}"))
        }
    })
}

impl Case {
    /// Every broken rule, with its key.
    pub fn violations(&self) -> Vec<Violation> {
        let mut all = Vec::new();
        let mut friction = Checker::new("friction");
        self.friction.check(&mut friction);
        all.extend(friction.violations);
        let mut time = Checker::new("time");
        self.time.check(&mut time);
        if let (Some(tolerance), SceneSpec::Point(_)) = (self.time.tolerance, &self.scene) {
            time.fail(
                "tolerance",
                tolerance,
                "is for dynamic scenes (spring_block, block, mesh); a point scene prescribes its motion",
            );
        }
        if let (false, SceneSpec::Point(_)) = (self.time.method.steps_a_point(), &self.scene) {
            time.fail(
                "integrator",
                self.time.method.name(),
                "is for dynamic scenes (spring_block, block, mesh); a point scene prescribes its motion",
            );
        }
        all.extend(time.violations);
        let mut scene = Checker::new("scene");
        self.scene.check(&mut scene);
        let valid = all.is_empty() && scene.violations.is_empty();
        all.extend(scene.violations);
        if valid {
            all.extend(self.initial_strength_violation());
        }
        let mut events = Checker::new("events");
        if let Some(threshold) = self.events.slip_rate_threshold {
            events.positive("slip_rate_threshold", threshold);
        }
        events.non_negative("merge_within", self.events.merge_within);
        all.extend(events.violations);
        let mut probes = Checker::new("probes");
        self.probes.check(&self.scene, &mut probes);
        all.extend(probes.violations);
        let mut record = Checker::new("record");
        self.record.check(&self.scene, &mut record);
        all.extend(record.violations);
        all
    }

    /// `f0` must lie on or inside the initial subloading surface of every loaded contact point
    /// (eq. 3 with `R ≤ 1`): `f0 ≤ μ_k (1/R*₀) f_n`, binding where `f_n` is smallest.
    fn initial_strength_violation(&self) -> Option<Violation> {
        let (f_n, key) = self.scene.weakest_normal_traction()?;
        let p = &self.friction;
        let strength = p.mu_k * p.initial_structure() * f_n;
        (p.f0 > strength).then(|| {
            let mut c = Checker::new("friction");
            c.fail(
                "f0",
                p.f0,
                format!(
                    "must not exceed the initial strength mu_k (1/R*) f_n = {} Pa of the weakest loaded contact \
                     point ({key} gives it f_n = {} Pa): the initial traction would lie outside the subloading surface",
                    shortest(strength),
                    shortest(f_n)
                ),
            );
            c.violations.remove(0)
        })
    }

    /// Reads the files the case names (a mesh) once its own rules hold, so that a broken rule
    /// is reported before a file is read.
    fn load_files(&mut self, dir: &Path) -> Result<(), CaseError> {
        if !matches!(self.scene, SceneSpec::Mesh(_)) {
            return Ok(());
        }
        let mut scene = Checker::new("scene");
        self.scene.check(&mut scene);
        if !scene.violations.is_empty() {
            return Err(CaseError::Invalid(scene.violations));
        }
        let friction = match self.source.table.get("friction") {
            Some(toml::Value::Table(table)) => table.clone(),
            _ => toml::Table::new(),
        };
        let SceneSpec::Mesh(mesh) = &mut self.scene else { unreachable!("checked above") };
        let violations = mesh.load(dir, &friction).map_err(CaseError::Mesh)?;
        if violations.is_empty() { Ok(()) } else { Err(CaseError::Invalid(violations)) }
    }

    /// Resolves `time.integrator`: the method named, or `auto`'s choice for the scene and why
    /// ([`choose`]).
    pub fn resolve(&mut self) {
        (self.time.method, self.time.chosen_because) = match self.time.integrator {
            Choice::Named(method) => (method, None),
            Choice::Auto => {
                let (method, why) = choose(self.problem());
                (method, Some(why))
            }
        };
    }

    /// What `time.integrator = "auto"` needs to know of the case ([`choose`]).
    pub fn problem(&self) -> Problem {
        let p = &self.friction;
        let healing = p.rstar_scale() * p.xi * p.n.max(1.0) * p.kinetic_static_ratio() * self.time.dt;
        match self.scene.unknowns() {
            None => Problem::Point,
            Some(unknowns) => {
                // Only a body small enough for the pair is bounded: a cell at a time, cheap there.
                let omega = (unknowns <= AUTO_PAIR_UNKNOWNS)
                    .then(|| self.scene.stiffest_frequency(p))
                    .flatten()
                    .filter(|omega| omega.is_finite());
                let stiffness = omega.map(|omega| omega * self.time.dt);
                // The drive's time to load the weakest point by its elastic slip at its static
                // strength, μ_s f_n / (α_t v), in radians of the stiffest mode.
                // Read only from a scene that holds its rules (a table's lengths, say): this runs
                // before the case's values are checked.
                let valid = {
                    let mut scene = Checker::new("scene");
                    self.scene.check(&mut scene);
                    scene.violations.is_empty()
                };
                let weakest = valid.then(|| self.scene.weakest_normal_traction()).flatten();
                let loading = omega
                    .zip(weakest)
                    .map(|(omega, (f_n, _))| omega * p.mu_s * f_n / (p.alpha_t * self.scene.driving_velocity()));
                let evolving = self.scene.has_evolving_normal();
                Problem::Body { unknowns, healing, stiffness, loading: loading.filter(|l| l.is_finite()), evolving }
            }
        }
    }

    /// Sets the step or tolerance that `time.accuracy` asks of the method ([`Method::for_accuracy`](crate::dynamics::Method::for_accuracy));
    /// refuses an accuracy whose fixed step would exceed the most steps a run may take.
    fn apply_accuracy(&mut self) -> Option<Violation> {
        let time = &mut self.time;
        let accuracy = time.accuracy?;
        let (dt, tolerance) = time.method.for_accuracy(accuracy, time.dt);
        if time.t_end / dt > MAX_STEPS {
            let mut c = Checker::new("time");
            c.fail(
                "accuracy",
                accuracy,
                format!(
                    "asks {} for steps of {} s: {:.3e} steps for t_end = {} s, more than the {MAX_STEPS:e} allowed",
                    time.method.name(),
                    shortest(dt),
                    time.t_end / dt,
                    shortest(time.t_end)
                ),
            );
            return c.violations.pop();
        }
        time.dt = dt;
        time.tolerance = tolerance.or(time.tolerance);
        None
    }

    /// Slip-rate threshold of the event catalog: given, or 10 × the driving velocity.
    pub fn slip_rate_threshold(&self) -> f64 {
        self.events.slip_rate_threshold.unwrap_or(10.0 * self.scene.driving_velocity())
    }

    /// How the case steps: its method with the numbers it needs.
    pub fn stepping(&self) -> Stepping {
        let time = &self.time;
        Stepping {
            method: time.method,
            dt: time.dt,
            tolerance: time.adaptive_tolerance(),
            dt_max: time.dt_max(),
            dt_min: time.dt_min(),
            slip_rate_threshold: self.slip_rate_threshold(),
        }
    }
}
