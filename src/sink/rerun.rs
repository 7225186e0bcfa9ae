//! The Rerun sink: every recorded step as time series on the `sim_time` and `step` timelines
//! ([`crate::sink::series`]), the slip front's state lanes and profiles
//! ([`crate::sink::slip_front`]), a spatial view of the deforming block with its contact
//! coloured by state, the space-time map ([`crate::sink::spacetime`]), the catalog as text logs,
//! the run's properties ([`crate::sink::properties`]) and a default blueprint
//! ([`crate::sink::blueprint`]).
//!
//! Rows are buffered and sent as columns (`send_columns` bypasses Rerun's batcher, so many
//! steps go as one chunk), at least every second and every 2 048 rows ([`crate::sink::cadence`]).
//! While no segment slips only every `stick_every`-th step is recorded.

use rerun::sink::SinkFlushError;
use rerun::{RecordingStream, TimeColumn};

use crate::catalog::events::Catalog;
use crate::frame::Ending;
use crate::frame::{Frame, Layout, Needs, SceneKind};
use crate::record::schema::{
    self, Decimator, RecordingPlan, RunEnding, RunInfo, ViewDecimator, selection, series_plan,
};
use crate::sink::blueprint::{self, Contents};
use crate::sink::cadence::Cadence;
use crate::sink::geometry::{self, GeometryBuffer};
use crate::sink::memory::RecordingMemory;
use crate::sink::recording_file::{FileFailure, RecordingFile};
use crate::sink::series::SeriesColumns;
use crate::sink::slip_front::SlipFront;
use crate::sink::spacetime::SpaceTime;
use crate::sink::viewer::DetachedViewer;
use crate::sink::{Continuation, Sink, SinkError, SinkMemory, properties, sync};

/// Geometry points buffered before every buffer is sent (large meshes flush sooner).
const GEOMETRY_POINTS_PER_CHUNK: usize = 2_000_000;

/// Writes a Rerun recording (file, viewer, or both).
pub struct RerunSink {
    rec: Option<RecordingStream>,
    plan: RecordingPlan,
    layout: Option<Layout>,
    steps: Vec<i64>,
    times: Vec<f64>,
    series: SeriesColumns,
    /// Which recorded steps get a frame of the drawn views, and those buffered.
    views: ViewDecimator,
    view_steps: Vec<i64>,
    view_times: Vec<f64>,
    slip_front: Option<SlipFront>,
    /// When the buffered rows go to the file ([`Cadence`]).
    cadence: Cadence,
    rows: u64,
    geometry: GeometryBuffer,
    decimator: Decimator,
    last_time: f64,
    spacetime: Option<SpaceTime>,
    needs: Needs,
    /// The step of the last frame seen.
    seen: u64,
    /// The file the stream writes, synced at each checkpoint.
    file: Option<std::path::PathBuf>,
    /// The first write error of the recording's file, set by its sink's thread.
    file_failure: Option<FileFailure>,
    /// The recording this one continues, for a resumed run.
    continuation: Option<Continuation>,
    /// Whether the static header [`Sink::begin`] logged may still be on its way to the file
    /// ([`RerunSink::header_written`]).
    header_pending: bool,
}

impl RerunSink {
    /// A sink over an open recording stream.
    pub fn new(stream: Stream, plan: RecordingPlan) -> Self {
        let Stream { rec, file, file_failure } = stream;
        rec.set_log_time_enabled(false);
        let needs = Needs {
            segment_state: plan.spec.quantities.iter().any(|q| q.needs_state()),
            surface_nodes: true,
            mesh: plan.spec.spatial,
        };
        Self {
            rec: Some(rec),
            decimator: Decimator::new(&plan),
            views: ViewDecimator::new(&plan),
            view_steps: Vec::new(),
            view_times: Vec::new(),
            plan,
            layout: None,
            steps: Vec::new(),
            times: Vec::new(),
            series: SeriesColumns::default(),
            slip_front: None,
            cadence: Cadence::default(),
            rows: 0,
            geometry: GeometryBuffer::default(),
            last_time: 0.0,
            spacetime: None,
            needs,
            seen: 0,
            file,
            file_failure,
            continuation: None,
            header_pending: false,
        }
    }

    /// Waits until the static header (run description, series styles, blueprint), which goes
    /// through Rerun's batcher, is in the file, before the first chunk that bypasses the
    /// batcher: the file then holds the header before any row, and a file cut early (an
    /// interrupted run, a full disk) still has it. [`Sink::begin`] only starts that flush, so
    /// that the header is encoded beside the first steps instead of before them; by the first
    /// rows' hand-over it is written and the wait is short.
    fn header_written(&mut self) -> Result<(), SinkError> {
        if std::mem::take(&mut self.header_pending) {
            flush(self.rec())?;
        }
        Ok(())
    }

    /// The recording file's first write error, if it had one ([`RecordingFile`]).
    fn file_written(&self) -> Result<(), SinkError> {
        match self.file_failure.as_ref().and_then(|failure| failure.get()) {
            Some(error) => Err(SinkError(error.clone())),
            None => Ok(()),
        }
    }

    /// The same sink continuing the recording of an interrupted run ([`Continuation`]).
    pub fn continuing(mut self, continuation: Continuation) -> Self {
        self.continuation = Some(continuation);
        self
    }

    /// Copies the continued recording's rows up to the checkpoint into this one, checks that
    /// they are all there, and continues the series' digests over them.
    fn continue_recording(&mut self, memory: &RecordingMemory) -> Result<(), SinkError> {
        let Some(continuation) = self.continuation.clone() else { return Ok(()) };
        self.header_written()?;
        let id = self.plan.recording_id.clone().unwrap_or_default();
        let through = memory.through as i64;
        let rec = self.rec.as_ref().expect("the stream lives until finish");
        let rows =
            crate::record::continuation::copy_recording(&continuation.previous, rec, &id, through, &[schema::EVENTS])
                .map_err(SinkError)?;
        let first = self.series.first_path().unwrap_or_default();
        let found = rows.iter().find(|(entity, _)| entity.trim_start_matches('/') == first).map_or(0, |(_, r)| *r);
        if found as u64 != memory.rows {
            return Err(SinkError(format!(
                "{} holds {found} recorded rows up to step {through}, where the checkpoint counts {}: it is not this \
                 run's recording up to its checkpoint",
                continuation.previous.display(),
                memory.rows
            )));
        }
        let recorded = crate::inspect::rrd::read(&continuation.previous).map_err(|e| SinkError(e.0))?;
        self.series.resume_digests(&recorded.series, through).map_err(SinkError)?;
        flush(self.rec())
    }

    fn rec(&self) -> &RecordingStream {
        self.rec.as_ref().expect("the stream lives until finish")
    }

    /// Appends one recorded step to the buffered columns, flushing them when due; `last` marks
    /// the run's last frame, which always gets a view frame.
    fn write_row(&mut self, frame: &Frame, last: bool) -> Result<(), SinkError> {
        self.steps.push(frame.step as i64);
        self.times.push(frame.time);
        self.series.push(frame);
        self.rows += 1;
        self.last_time = frame.time;
        if let Some(front) = &mut self.slip_front {
            front.push_state(frame);
        }
        if let Some(map) = &mut self.spacetime {
            map.push(frame.time, frame.segments.iter().map(|s| s.slip_rate));
        }
        let last = last || frame.time >= self.plan.t_end * (1.0 - 1e-12);
        let view = if last { self.views.keep_last(frame) } else { self.views.keep(frame) };
        if self.plan.spec.spatial && view {
            self.view_steps.push(frame.step as i64);
            self.view_times.push(frame.time);
            let layout = self.layout.as_ref().expect("begin() ran");
            self.geometry.push(frame, layout, &self.plan);
            if let Some(front) = &mut self.slip_front {
                front.push_profiles(frame);
            }
        }
        if self.cadence.row() || self.geometry.points() >= GEOMETRY_POINTS_PER_CHUNK {
            self.flush_columns()?;
            // Hand the file sink's buffer to the disk too, without waiting for a viewer.
            self.rec().flush_async().map_err(rerun_error)?;
            // A write error of an earlier flush stops the run now, not at its end.
            self.file_written()?;
        }
        Ok(())
    }

    /// Sends the buffered rows of every entity, one chunk each.
    fn flush_columns(&mut self) -> Result<(), SinkError> {
        if self.steps.is_empty() {
            return Ok(());
        }
        self.header_written()?;
        if crate::sink::WITHOUT_RERUN {
            return self.drop_columns();
        }
        let columns = |steps: &mut Vec<i64>, times: &mut Vec<f64>| {
            [
                TimeColumn::new_sequence(schema::STEP, std::mem::take(steps)),
                TimeColumn::new_duration_secs(schema::SIM_TIME, std::mem::take(times)),
            ]
        };
        let view_times = columns(&mut self.view_steps, &mut self.view_times);
        let rec = self.rec.as_ref().expect("the stream lives until finish");
        self.series.send(rec, &self.steps, &self.times).map_err(rerun_error)?;
        self.steps.clear();
        self.times.clear();
        if let Some(front) = &mut self.slip_front {
            front.send(rec, &view_times).map_err(rerun_error)?;
        }
        for (entity, columns) in self.geometry.take().map_err(rerun_error)? {
            rec.send_columns(entity, view_times.clone(), columns).map_err(rerun_error)?;
        }
        Ok(())
    }

    /// A measuring build's hand-over ([`crate::sink::WITHOUT_RERUN`]): the series' digests
    /// continue as in [`Self::flush_columns`], and every buffered row is dropped.
    fn drop_columns(&mut self) -> Result<(), SinkError> {
        self.series.discard(&self.steps, &self.times);
        for buffer in [&mut self.steps, &mut self.view_steps] {
            buffer.clear();
        }
        for buffer in [&mut self.times, &mut self.view_times] {
            buffer.clear();
        }
        if let Some(front) = &mut self.slip_front {
            front.discard();
        }
        self.geometry.discard();
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
                    "{:.1} s: {} slips to {:.1} s, {:.2e} m, peak {:.1e} m/s, f_t {:.1} → {:.1} Pa",
                    e.onset,
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
        if layout.kind.has_body() {
            for r in &catalog.ruptures {
                rec.set_duration_secs(schema::SIM_TIME, r.onset);
                rec.log(
                    schema::EVENTS,
                    &rerun::TextLog::new(format!(
                        "{:.1} s: rupture from {}, segments {} to {} ({} slipped) to {:.1} s, max slip {:.2e} m, force drop {:.1} {}",
                        r.onset,
                        name(r.nucleation_segment),
                        r.first_segment,
                        r.last_segment,
                        r.segments_slipped,
                        r.end,
                        r.max_slip,
                        r.friction_force_drop,
                        layout.force_unit()
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
        let front = spatial.then(|| SlipFront::new(layout, &segments, self.plan.slip_rate_threshold, self.plan.mu_k));
        self.needs.surface_nodes = !nodes.is_empty();
        self.needs.mesh = spatial && layout.mesh.is_some();
        self.needs.segment_state |= front.as_ref().is_some_and(SlipFront::needs_state);
        let plan = series_plan(layout, &segments, &nodes, &self.plan.spec.quantities);
        let info = RunInfo::new(&self.plan, layout, &segments, &nodes, &plan, spatial);
        let rec = self.rec.as_ref().expect("the stream lives until finish");
        let text = toml::to_string(&info).map_err(|e| SinkError(format!("cannot describe the run: {e}")))?;
        rec.log_static(
            schema::RUN_INFO,
            &rerun::TextDocument::new(text).with_media_type(rerun::MediaType::plain_text()),
        )
        .map_err(rerun_error)?;
        properties::log(rec, &self.plan, &info).map_err(rerun_error)?;
        self.series.begin(rec, plan).map_err(rerun_error)?;
        if let Some(front) = &front {
            front.begin(rec, layout).map_err(rerun_error)?;
            geometry::log_styles(rec, layout).map_err(rerun_error)?;
        }
        let contents = Contents {
            layout,
            segments: &segments,
            nodes: &nodes,
            spatial,
            magnification: self.plan.spec.magnification,
            t_end: self.plan.t_end,
            slip_rate_threshold: self.plan.slip_rate_threshold,
            profiles: front.as_ref().map_or_else(Vec::new, SlipFront::profile_entities),
        };
        blueprint::send(rec, &contents).map_err(rerun_error)?;
        // The columns go to the file directly (`send_columns` bypasses the batcher): the header
        // must reach the file before them ([`RerunSink::header_written`]).
        rec.flush_async().map_err(rerun_error)?;
        self.header_pending = true;
        self.slip_front = front;
        self.spacetime = spatial.then(|| SpaceTime::new(self.plan.t_end, layout.segments.len()));
        self.plan.spec.spatial = spatial;
        self.layout = Some(layout.clone());
        Ok(())
    }

    fn record(&mut self, frame: &Frame) -> Result<(), SinkError> {
        self.seen = frame.step;
        if self.decimator.keep(frame) { self.write_row(frame, false) } else { Ok(()) }
    }

    fn writes(&self, frame: &Frame) -> bool {
        self.decimator.would_keep(frame)
    }

    fn checkpoint(&mut self) -> Result<SinkMemory, SinkError> {
        self.flush_columns()?;
        flush(self.rec())?;
        if let Some(file) = &self.file {
            sync(file)?;
        }
        Ok(SinkMemory::Recording(RecordingMemory {
            through: self.seen,
            rows: self.rows,
            last_time: self.last_time,
            digests: self.series.digests(),
            decimator: self.decimator.memory(),
            views: self.views.memory(),
            slip_front: self.slip_front.as_ref().and_then(SlipFront::memory),
            spacetime: self.spacetime.as_ref().map(SpaceTime::memory),
        }))
    }

    fn resume(&mut self, saved: &[SinkMemory]) -> Result<(), SinkError> {
        let Some(memory) = saved.iter().find_map(|m| match m {
            SinkMemory::Recording(memory) => Some(memory),
            _ => None,
        }) else {
            return Err(SinkError("the checkpoint's run wrote no recording to continue".into()));
        };
        self.continue_recording(memory)?;
        (self.seen, self.rows, self.last_time) = (memory.through, memory.rows, memory.last_time);
        self.decimator.resume(memory.decimator);
        self.views.resume(memory.views.clone());
        if let Some(front) = &mut self.slip_front {
            front.resume(memory.slip_front.clone());
        }
        if let (Some(map), Some(saved)) = (&mut self.spacetime, &memory.spacetime) {
            map.resume(saved.clone(), self.plan.t_end).map_err(SinkError)?;
        }
        Ok(())
    }

    fn finish(&mut self, ending: Ending, last: Option<&Frame>, catalog: &Catalog) -> Result<(), SinkError> {
        if self.rec.is_none() {
            return Ok(());
        }
        let mut result = match last {
            Some(frame) if self.layout.is_some() && self.decimator.keep_last(frame) => self.write_row(frame, true),
            _ => Ok(()),
        };
        result = result.and(self.flush_columns());
        if let Some(layout) = &self.layout {
            if let Some(map) = &self.spacetime {
                result = result.and(map.log(self.rec(), layout, self.plan.slip_rate_threshold).map_err(rerun_error));
            }
            result = result.and(self.log_catalog(catalog));
            let digests = self.series.digests();
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

/// Flushes `rec` within [`FLUSH_TIMEOUT`]; a sink that failed names its error (the file's is
/// the operating system's, e.g. "No space left on device").
fn flush(rec: &RecordingStream) -> Result<(), SinkError> {
    rec.flush_with_timeout(FLUSH_TIMEOUT).map_err(|e| match e {
        SinkFlushError::Timeout => SinkError(format!(
            "cannot flush the recording within {} s: is a connected viewer still reading?",
            FLUSH_TIMEOUT.as_secs()
        )),
        SinkFlushError::Failed { message } => SinkError(message),
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
) -> Result<Option<Stream>, String> {
    use rerun::sink::{GrpcSink, LogSink};
    let uri: Option<String> = match viewer {
        Viewer::None => None,
        Viewer::Spawn => {
            if find_on_path("rerun").is_none() {
                return Err("--spawn needs the Rerun viewer, but `rerun` is not on PATH; install it with \
                            `pip install rerun-sdk==0.36.3` (or `cargo install rerun-cli@0.36.3`), or use --connect URL"
                    .into());
            }
            if !has_display() {
                return Err(format!(
                    "--spawn opens the Rerun viewer in a window, and this session has no display \
                     (DISPLAY and WAYLAND_DISPLAY are unset); {}",
                    without_a_window(file)
                ));
            }
            let options = rerun::SpawnOptions { wait_for_bind: true, ..Default::default() };
            let spawned = rerun::spawn(&options).map_err(|e| format!("cannot start the Rerun viewer: {e}"))?;
            Some(format!("rerun+http://127.0.0.1:{}/proxy", spawned.port))
        }
        Viewer::Connect(url) => Some(url.clone()),
    };
    let unreachable = |url: &str, e: String| match viewer {
        Viewer::Spawn => format!(
            "the Rerun viewer started by --spawn did not listen (its own message, if any, is above): {e}; {}",
            without_a_window(file)
        ),
        _ => format!("--connect {url}: {e} (start one with `rerun`, or use --spawn)"),
    };
    let grpc = match &uri {
        None => None,
        Some(url) => {
            let parsed: rerun::external::re_uri::ProxyUri = url.parse().map_err(|e| {
                format!("--connect {url}: not a Rerun viewer URL ({e}); e.g. rerun+http://127.0.0.1:9876/proxy")
            })?;
            let address = format!("{}:{}", parsed.origin.host, parsed.origin.port);
            crate::sink::viewer::answers(&address).map_err(|e| unreachable(url, e))?;
            Some(DetachedViewer::connect(GrpcSink::new(parsed), url)?)
        }
    };
    let mut builder =
        rerun::RecordingStreamBuilder::new(schema::APP_ID).recording_name(name).enabled(!crate::sink::WITHOUT_RERUN);
    if let Some(id) = id {
        builder = builder.recording_id(id);
    }
    let path = file.map(std::path::Path::to_path_buf);
    let file = file.map(RecordingFile::create).transpose()?;
    let file_failure = file.as_ref().map(RecordingFile::failure);
    let mut sinks: Vec<Box<dyn LogSink>> = Vec::new();
    sinks.extend(file.map(|f| Box::new(f) as Box<dyn LogSink>));
    sinks.extend(grpc.map(|g| Box::new(g) as Box<dyn LogSink>));
    if sinks.is_empty() {
        return Ok(None);
    }
    crate::sink::heap::keep_freed_blocks();
    let rec = builder.set_sinks(sinks).map_err(|e| format!("cannot open the recording: {e}"))?;
    Ok(Some(Stream { rec, file: path, file_failure }))
}

/// Whether a window can be opened: an X11 or Wayland display is named in the environment.
pub fn has_display() -> bool {
    ["DISPLAY", "WAYLAND_DISPLAY", "WAYLAND_SOCKET"].iter().any(|v| std::env::var_os(v).is_some_and(|d| !d.is_empty()))
}

/// What works where no viewer window opens: the recording opened later, or a viewer elsewhere.
fn without_a_window(file: Option<&std::path::Path>) -> String {
    let later = match file {
        Some(path) => format!(
            "run without --spawn and open the recording later where there is a display (`rerun {}`)",
            path.display()
        ),
        None => "run without --spawn and --no-rrd and open the recording later where there is a display".to_string(),
    };
    format!("{later}, or stream to a viewer running elsewhere with --connect rerun+http://HOST:9876/proxy")
}

/// An open recording stream, and the file it writes, if any, with that file's first write
/// error.
pub struct Stream {
    pub rec: RecordingStream,
    pub file: Option<std::path::PathBuf>,
    pub file_failure: Option<FileFailure>,
}

/// The first executable called `name` on `PATH`.
pub fn find_on_path(name: &str) -> Option<std::path::PathBuf> {
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths).map(|dir| dir.join(name)).find(|candidate| {
            use std::os::unix::fs::PermissionsExt;
            candidate.metadata().is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
        })
    })
}
