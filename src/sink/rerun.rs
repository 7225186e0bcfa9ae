//! The Rerun sink: every recorded step as time series on the `sim_time` and `step` timelines,
//! a spatial view of the deforming block with its contact coloured by state, a space-time
//! view of slip rate, the catalog as text logs, and a default blueprint ([`crate::sink::blueprint`]).
//!
//! Time series are buffered and sent as columns (`send_columns` bypasses Rerun's batcher, so
//! many steps go as one chunk), at least every second and every 512 rows
//! ([`crate::sink::cadence`]); geometry is logged row by row on recorded steps. While no
//! segment slips only every `stick_every`-th step is recorded.

use rerun::{RecordingStream, Scalars, SeriesLines, TimeColumn};

use crate::catalog::events::Catalog;
use crate::frame::Ending;
use crate::frame::{Frame, Layout, Needs, SceneKind};
use crate::record::colormap::{POSITION, SLIP_RATE, sample};
use crate::record::digest::SeriesDigest;
use crate::record::schema::{self, Decimator, RecordingPlan, RunEnding, RunInfo, Source, selection, series_plan};
use crate::sink::blueprint::default_blueprint;
use crate::sink::cadence::{self, Cadence};
use crate::sink::geometry::{GeometryBuffer, SPACETIME_ROWS, spacetime_width};
use crate::sink::viewer::DetachedViewer;
use crate::sink::{Sink, SinkError};

/// Geometry points buffered before every buffer is sent (large meshes flush sooner).
const GEOMETRY_POINTS_PER_CHUNK: usize = 2_000_000;

/// Writes a Rerun recording (file, viewer, or both).
pub struct RerunSink {
    rec: Option<RecordingStream>,
    plan: RecordingPlan,
    layout: Option<Layout>,
    series: Vec<(String, Source)>,
    steps: Vec<i64>,
    times: Vec<f64>,
    values: Vec<Vec<f64>>,
    /// The digest of each series' rows so far ([`SeriesDigest`]).
    digests: Vec<SeriesDigest>,
    /// When the buffered rows go to the file ([`Cadence`]).
    cadence: Cadence,
    rows: u64,
    geometry: GeometryBuffer,
    decimator: Decimator,
    last_time: f64,
    /// Peak slip rate per (time row, segment) for the space-time image.
    spacetime: Vec<f32>,
    needs: Needs,
}

impl RerunSink {
    /// A sink over an open recording stream.
    pub fn new(rec: RecordingStream, plan: RecordingPlan) -> Self {
        rec.set_log_time_enabled(false);
        let needs = Needs {
            segment_state: plan.spec.quantities.iter().any(|q| q.needs_state()),
            surface_nodes: true,
            mesh: plan.spec.spatial,
        };
        Self {
            rec: Some(rec),
            decimator: Decimator::new(&plan),
            plan,
            layout: None,
            series: Vec::new(),
            steps: Vec::new(),
            times: Vec::new(),
            values: Vec::new(),
            digests: Vec::new(),
            cadence: Cadence::default(),
            rows: 0,
            geometry: GeometryBuffer::default(),
            last_time: 0.0,
            spacetime: Vec::new(),
            needs,
        }
    }

    fn rec(&self) -> &RecordingStream {
        self.rec.as_ref().expect("the stream lives until finish")
    }

    /// Appends one recorded step to the buffered columns, flushing them when full.
    fn write_row(&mut self, frame: &Frame) -> Result<(), SinkError> {
        self.steps.push(frame.step as i64);
        self.times.push(frame.time);
        for (((_, source), values), digest) in self.series.iter().zip(&mut self.values).zip(&mut self.digests) {
            let value = source.of(frame);
            values.push(value);
            digest.add(frame.step as i64, frame.time, value);
        }
        self.rows += 1;
        self.last_time = frame.time;
        if self.plan.spec.spatial {
            // Recorded steps only, so that a replayed log draws the same image.
            let segments = frame.segments.len();
            let row = ((frame.time / self.plan.t_end * SPACETIME_ROWS as f64) as usize).min(SPACETIME_ROWS - 1);
            for (k, s) in frame.segments.iter().enumerate() {
                let cell = &mut self.spacetime[row * segments + k];
                *cell = cell.max(s.slip_rate as f32);
            }
            let layout = self.layout.as_ref().expect("begin() ran");
            self.geometry.push(frame, layout, &self.plan);
        }
        if self.cadence.row() || self.geometry.points() >= GEOMETRY_POINTS_PER_CHUNK {
            self.flush_columns()?;
            // Hand the file sink's buffer to the disk too, without waiting for a viewer.
            self.rec().flush_async().map_err(rerun_error)?;
        }
        Ok(())
    }

    /// Sends the buffered rows of every series and geometry entity, one chunk each.
    fn flush_columns(&mut self) -> Result<(), SinkError> {
        if self.steps.is_empty() {
            return Ok(());
        }
        let steps = TimeColumn::new_sequence(schema::STEP, std::mem::take(&mut self.steps));
        let times = TimeColumn::new_duration_secs(schema::SIM_TIME, std::mem::take(&mut self.times));
        let rec = self.rec.as_ref().expect("the stream lives until finish");
        for ((path, _), values) in self.series.iter().zip(&mut self.values) {
            let column = Scalars::new(std::mem::take(values)).columns_of_unit_batches().map_err(rerun_error)?;
            rec.send_columns(path.as_str(), [steps.clone(), times.clone()], column).map_err(rerun_error)?;
        }
        for (entity, columns) in self.geometry.take().map_err(rerun_error)? {
            rec.send_columns(entity, [steps.clone(), times.clone()], columns).map_err(rerun_error)?;
        }
        Ok(())
    }

    /// The space-time image: rows are time bins over `[0, t_end]`, columns segments, colour
    /// the bin's peak slip rate on a log scale from a hundredth of the threshold to the peak.
    fn log_spacetime(&self) -> Result<(), SinkError> {
        let segments = self.layout.as_ref().map_or(1, |l| l.segments.len());
        let width = spacetime_width(segments);
        let px = width / segments;
        let floor = self.plan.slip_rate_threshold / 100.0;
        let peak = self.spacetime.iter().fold(0.0_f32, |m, v| m.max(*v)) as f64;
        let top = peak.max(self.plan.slip_rate_threshold * 10.0);
        let mut rgb = Vec::with_capacity(width * SPACETIME_ROWS * 3);
        for row in 0..SPACETIME_ROWS {
            for k in 0..segments {
                let rate = self.spacetime[row * segments + k] as f64;
                let t =
                    if rate <= floor { 0.0 } else { ((rate / floor).log10() / (top / floor).log10()).clamp(0.0, 1.0) };
                let colour = sample(&SLIP_RATE, t);
                for _ in 0..px {
                    rgb.extend_from_slice(&colour);
                }
            }
        }
        let rec = self.rec();
        rec.log_static(schema::SPACETIME_IMAGE, &rerun::Image::from_rgb24(rgb, [width as u32, SPACETIME_ROWS as u32]))
            .map_err(rerun_error)?;
        rec.log_static(
            format!("{}/scale", schema::SPACETIME),
            &rerun::TextDocument::new(format!(
                "Space-time view: segments from the left across ({px} px each), time down ({:.4} s per row over [0, {} s]). \
                 Colour: peak slip rate in the row, log scale from {floor:.3e} m/s (black) to {top:.3e} m/s (yellow).",
                self.plan.t_end / SPACETIME_ROWS as f64,
                self.plan.t_end
            )),
        )
        .map_err(rerun_error)?;
        Ok(())
    }

    fn log_catalog(&self, catalog: &Catalog) -> Result<(), SinkError> {
        let layout = self.layout.as_ref().expect("begin() ran");
        let name = |k: usize| match &layout.segments[k].name {
            Some(n) => format!("segment {k} ({n})"),
            None => format!("segment {k}"),
        };
        let rec = self.rec();
        rec.reset_time();
        for e in &catalog.events {
            rec.set_duration_secs(schema::SIM_TIME, e.onset);
            rec.log(
                schema::EVENTS,
                &rerun::TextLog::new(format!(
                    "{} slips until {:.3} s: {:.4} m, peak {:.3e} m/s, f_t {:.2} -> {:.2} Pa",
                    name(e.segment),
                    e.end,
                    e.slip,
                    e.peak_slip_rate,
                    e.traction_before,
                    e.traction_after
                ))
                .with_level(rerun::TextLogLevel::INFO),
            )
            .map_err(rerun_error)?;
        }
        if layout.kind == SceneKind::Block {
            for r in &catalog.ruptures {
                rec.set_duration_secs(schema::SIM_TIME, r.onset);
                rec.log(
                    schema::EVENTS,
                    &rerun::TextLog::new(format!(
                        "rupture nucleated at {}: segments {}-{} ({} slipped) until {:.3} s, max slip {:.4} m, friction force drop {:.2} {}",
                        name(r.nucleation_segment),
                        r.first_segment,
                        r.last_segment,
                        r.segments_slipped,
                        r.end,
                        r.max_slip,
                        r.friction_force_drop,
                        layout.kind.force_unit()
                    ))
                    .with_level(rerun::TextLogLevel::WARN),
                )
                .map_err(rerun_error)?;
            }
        }
        Ok(())
    }
}

impl Sink for RerunSink {
    fn needs(&self) -> Needs {
        self.needs
    }

    fn begin(&mut self, layout: &Layout) -> Result<(), SinkError> {
        let (segments, nodes) = selection(&self.plan.spec, layout);
        let spatial = self.plan.spec.spatial && layout.kind != SceneKind::Point;
        self.needs.surface_nodes = !nodes.is_empty();
        self.needs.mesh = spatial && layout.mesh.is_some();
        let plan = series_plan(layout, &segments, &nodes, &self.plan.spec.quantities);
        let rec = self.rec.as_ref().expect("the stream lives until finish");
        for series in &plan {
            let [r, g, b] = series.position.map_or([200, 200, 200], |x| sample(&POSITION, x));
            rec.log_static(
                series.path.as_str(),
                &SeriesLines::new().with_names([series.label.as_str()]).with_colors([rerun::Color::from_rgb(r, g, b)]),
            )
            .map_err(rerun_error)?;
        }
        let info = RunInfo::new(&self.plan, layout, &segments, &nodes, &plan, spatial);
        let text = toml::to_string(&info).map_err(|e| SinkError(format!("cannot describe the run: {e}")))?;
        rec.log_static(
            schema::RUN_INFO,
            &rerun::TextDocument::new(text).with_media_type(rerun::MediaType::plain_text()),
        )
        .map_err(rerun_error)?;
        default_blueprint(layout, &segments, &nodes, spatial, self.plan.spec.magnification)
            .send(rec, rerun::blueprint::BlueprintActivation { make_active: true, make_default: true })
            .map_err(rerun_error)?;
        // The columns go to the file directly (`send_columns` bypasses the batcher): without a
        // flush here, a fast run's first columns can reach the file before the run description,
        // and a file cut early (an interrupted run, a full disk) would lack it.
        flush(rec)?;
        self.values = vec![Vec::with_capacity(cadence::ROWS); plan.len()];
        self.digests = vec![SeriesDigest::default(); plan.len()];
        self.series = plan.into_iter().map(|s| (s.path, s.source)).collect();
        self.spacetime = vec![0.0; SPACETIME_ROWS * layout.segments.len()];
        self.plan.spec.spatial = spatial;
        self.layout = Some(layout.clone());
        Ok(())
    }

    fn record(&mut self, frame: &Frame) -> Result<(), SinkError> {
        if self.decimator.keep(frame) { self.write_row(frame) } else { Ok(()) }
    }

    fn finish(&mut self, ending: Ending, last: Option<&Frame>, catalog: &Catalog) -> Result<(), SinkError> {
        if self.rec.is_none() {
            return Ok(());
        }
        let mut result = match last {
            Some(frame) if self.layout.is_some() && self.decimator.keep_last(frame) => self.write_row(frame),
            _ => Ok(()),
        };
        result = result.and(self.flush_columns());
        if self.layout.is_some() {
            if self.plan.spec.spatial {
                result = result.and(self.log_spacetime());
            }
            result = result.and(self.log_catalog(catalog));
            let digests = self.series.iter().zip(&self.digests).map(|((path, _), d)| (path.clone(), d.hex())).collect();
            let summary = RunEnding::new(ending, self.last_time, self.rows, catalog, digests);
            let text = toml::to_string(&summary).map_err(|e| SinkError(format!("cannot describe the ending: {e}")))?;
            result = result.and(
                self.rec()
                    .log_static(
                        schema::RUN_ENDING,
                        &rerun::TextDocument::new(text).with_media_type(rerun::MediaType::plain_text()),
                    )
                    .map_err(rerun_error),
            );
        }
        // Dropping the last handle flushes the batcher and writes the file's footer.
        let rec = self.rec.take().expect("checked above");
        let flushed = flush(&rec);
        drop(rec);
        result.and(flushed)
    }
}

/// How long a flush may wait for the file and a connected viewer to take what was logged: a
/// viewer that accepted the connection but stopped reading must not stall the run for ever.
const FLUSH_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(20);

/// Flushes `rec` within [`FLUSH_TIMEOUT`].
fn flush(rec: &RecordingStream) -> Result<(), SinkError> {
    rec.flush_with_timeout(FLUSH_TIMEOUT).map_err(|e| {
        SinkError(format!(
            "cannot flush the recording within {} s ({e}): is a connected viewer still reading?",
            FLUSH_TIMEOUT.as_secs()
        ))
    })
}

fn rerun_error(e: impl std::fmt::Display) -> SinkError {
    SinkError(format!("recording: {e}"))
}

/// Where a live copy of the recording goes, besides the file.
#[derive(Debug, Clone, PartialEq)]
pub enum Viewer {
    None,
    /// Start the `rerun` executable found on `PATH`.
    Spawn,
    /// A running viewer's gRPC proxy, e.g. `rerun+http://127.0.0.1:9876/proxy`.
    Connect(String),
}

/// Opens a recording stream writing to `file` and/or a viewer; `None` if neither is asked for.
/// `id` is the recording id ([`schema::recording_id`]); `None` lets Rerun draw a random one. A
/// viewer that cannot be reached is an error here, before the run: a stream to an unreachable
/// viewer would block the file once its queue filled.
pub fn open_stream(
    file: Option<&std::path::Path>,
    viewer: &Viewer,
    name: &str,
    id: Option<&str>,
) -> Result<Option<RecordingStream>, String> {
    use rerun::sink::{FileSink, GrpcSink, LogSink};
    let uri: Option<String> = match viewer {
        Viewer::None => None,
        Viewer::Spawn => {
            if find_on_path("rerun").is_none() {
                return Err("--spawn needs the Rerun viewer, but `rerun` is not on PATH; install it with \
                            `pip install rerun-sdk==0.36.3` (or `cargo install rerun-cli@0.36.3`), or use --connect URL"
                    .into());
            }
            let options = rerun::SpawnOptions { wait_for_bind: true, ..Default::default() };
            let spawned = rerun::spawn(&options).map_err(|e| format!("cannot start the Rerun viewer: {e}"))?;
            Some(format!("rerun+http://127.0.0.1:{}/proxy", spawned.port))
        }
        Viewer::Connect(url) => Some(url.clone()),
    };
    let grpc = match &uri {
        None => None,
        Some(url) => {
            let parsed: rerun::external::re_uri::ProxyUri = url.parse().map_err(|e| {
                format!("--connect {url}: not a Rerun viewer URL ({e}); e.g. rerun+http://127.0.0.1:9876/proxy")
            })?;
            let address = format!("{}:{}", parsed.origin.host, parsed.origin.port);
            crate::sink::viewer::answers(&address).map_err(|e| format!("--connect {url}: {e}"))?;
            Some(DetachedViewer::connect(GrpcSink::new(parsed), url)?)
        }
    };
    let mut builder = rerun::RecordingStreamBuilder::new(schema::APP_ID).recording_name(name).enabled(true);
    if let Some(id) = id {
        builder = builder.recording_id(id);
    }
    let stream = match (file, grpc) {
        (None, None) => return Ok(None),
        (Some(path), None) => builder.save(path),
        (Some(path), Some(grpc)) => {
            let file = FileSink::new(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            builder.set_sinks(vec![Box::new(file) as Box<dyn LogSink>, Box::new(grpc)])
        }
        (None, Some(grpc)) => builder.set_sinks(vec![Box::new(grpc) as Box<dyn LogSink>]),
    };
    stream.map(Some).map_err(|e| format!("cannot open the recording: {e}"))
}

/// The first executable called `name` on `PATH`.
fn find_on_path(name: &str) -> Option<std::path::PathBuf> {
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths).map(|dir| dir.join(name)).find(|candidate| {
            use std::os::unix::fs::PermissionsExt;
            candidate.metadata().is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
        })
    })
}
