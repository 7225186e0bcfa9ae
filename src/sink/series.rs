//! The recording's scalar time series as buffered columns: one multi-instance `Scalars`
//! entity per quantity (one instance per recorded segment or node) and one per total, each with
//! a static `SeriesLines` naming and colouring its instances, as Rerun recommends for many
//! related series.

use std::collections::BTreeMap;

use rerun::{RecordingStream, Scalars, SeriesLines, TimeColumn};

use crate::frame::Frame;
use crate::record::colormap::{POSITION, sample};
use crate::record::digest::SeriesDigest;
use crate::record::schema::{self, EntitySpec, Source};

/// One entity's buffered rows.
struct Columns {
    path: String,
    sources: Vec<Source>,
    /// Row-major: `sources.len()` values per row.
    values: Vec<f64>,
    /// One per instance, over every row written so far.
    digests: Vec<SeriesDigest>,
    names: Vec<String>,
}

/// The scalar entities of a run, buffered between flushes.
#[derive(Default)]
pub struct SeriesColumns {
    entities: Vec<Columns>,
    rows: usize,
    /// The buffered rows' steps and times as the digests hash them ([`SeriesDigest::add_rows`]).
    row_bytes: Vec<u8>,
}

impl SeriesColumns {
    /// Logs each entity's static `SeriesLines` (names and colours by position along the
    /// surface) and prepares its buffers.
    pub fn begin(&mut self, rec: &RecordingStream, plan: Vec<EntitySpec>) -> rerun::RecordingStreamResult<()> {
        for spec in &plan {
            let colours = spec.positions.iter().map(|p| {
                let [r, g, b] = p.map_or([200, 200, 200], |x| sample(&POSITION, x));
                rerun::Color::from_rgb(r, g, b)
            });
            rec.log_static(
                spec.path.as_str(),
                &SeriesLines::new().with_names(spec.labels.iter().map(String::as_str)).with_colors(colours),
            )?;
        }
        self.entities = plan
            .into_iter()
            .map(|spec| Columns {
                names: spec.series_names(),
                digests: vec![SeriesDigest::default(); spec.sources.len()],
                // Room for the most rows a hand-over holds: the buffer does not grow in the run.
                values: Vec::with_capacity(spec.sources.len() * crate::sink::cadence::ROWS),
                path: spec.path,
                sources: spec.sources,
            })
            .collect();
        Ok(())
    }

    /// Appends `frame`'s values to every entity.
    pub fn push(&mut self, frame: &Frame) {
        for entity in &mut self.entities {
            entity.values.extend(entity.sources.iter().map(|source| source.of(frame)));
        }
        self.rows += 1;
    }

    /// Continues every series' digest over the buffered rows, whose steps and seconds are given.
    fn digest(&mut self, steps: &[i64], seconds: &[f64]) {
        SeriesDigest::rows_template(steps, seconds, &mut self.row_bytes);
        for entity in &mut self.entities {
            let width = entity.sources.len();
            for (i, digest) in entity.digests.iter_mut().enumerate() {
                digest.add_rows(&mut self.row_bytes, entity.values.iter().skip(i).step_by(width).copied());
            }
        }
    }

    /// Sends the buffered rows, one chunk per entity, on the time columns of their `steps` and
    /// `seconds`, and continues the series' digests over them.
    pub fn send(&mut self, rec: &RecordingStream, steps: &[i64], seconds: &[f64]) -> Result<(), String> {
        let rows = std::mem::take(&mut self.rows);
        if rows == 0 {
            return Ok(());
        }
        self.digest(steps, seconds);
        let times = [
            TimeColumn::new_sequence(schema::STEP, steps.to_vec()),
            TimeColumn::new_duration_secs(schema::SIM_TIME, seconds.to_vec()),
        ];
        for entity in &mut self.entities {
            let width = entity.sources.len();
            // Rerun copies the values into its own array; the buffer is kept for the next rows.
            let column = Scalars::new(entity.values.iter().copied())
                .columns(std::iter::repeat_n(width, rows))
                .map_err(|e| e.to_string())?;
            entity.values.clear();
            rec.send_columns(entity.path.as_str(), times.clone(), column).map_err(|e| e.to_string())?;
        }
        Ok(())
    }

    /// Continues every series' digest over the rows of `recorded` (a reader's series, by the
    /// name it gives them) up to step `through`: the rows a resumed run's recording starts with.
    pub fn resume_digests(
        &mut self,
        recorded: &BTreeMap<String, crate::inspect::Series>,
        through: i64,
    ) -> Result<(), String> {
        for entity in &mut self.entities {
            for (name, digest) in entity.names.iter().zip(&mut entity.digests) {
                let series = recorded.get(name).ok_or_else(|| format!("the recording has no series {name}"))?;
                let rows = series.steps.iter().zip(&series.times).zip(&series.values);
                for ((&step, &time), &value) in rows.take_while(|((step, _), _)| **step <= through) {
                    digest.add(step, time, value);
                }
            }
        }
        Ok(())
    }

    /// Continues the series' digests over the buffered rows and drops them, sending nothing
    /// (a measuring build's hand-over, [`crate::sink::WITHOUT_RERUN`]).
    pub fn discard(&mut self, steps: &[i64], seconds: &[f64]) {
        if std::mem::take(&mut self.rows) > 0 {
            self.digest(steps, seconds);
        }
        for entity in &mut self.entities {
            entity.values.clear();
        }
    }

    /// The path of the first entity, if any.
    pub fn first_path(&self) -> Option<&str> {
        self.entities.first().map(|e| e.path.as_str())
    }

    /// The digest of every series written so far, by the name a reader gives it.
    pub fn digests(&self) -> BTreeMap<String, String> {
        self.entities
            .iter()
            .flat_map(|e| e.names.iter().cloned().zip(e.digests.iter().map(SeriesDigest::hex)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::{Quantity, SegmentSample};

    fn plan() -> Vec<EntitySpec> {
        vec![
            EntitySpec {
                path: "contact/traction_t".to_string(),
                sources: vec![Source::Segment(0, Quantity::TractionT), Source::Segment(1, Quantity::TractionT)],
                labels: vec!["a".to_string(), "b".to_string()],
                positions: vec![Some(0.25), Some(0.75)],
            },
            EntitySpec {
                path: "totals/friction_force".to_string(),
                sources: vec![Source::FrictionForce],
                labels: vec!["F".to_string()],
                positions: vec![None],
            },
        ]
    }

    fn frame(step: u64) -> Frame {
        let t = step as f64;
        let segment = |k: f64| SegmentSample { traction_t: 1e3 * k + t.sin(), ..SegmentSample::default() };
        Frame {
            step,
            time: 0.01 * t,
            segments: vec![segment(1.0), segment(2.0)],
            friction_force: t.cos(),
            ..Frame::default()
        }
    }

    /// Two hand-overs of `rows` rows each, sent or (a measuring build's) dropped.
    fn digests_after(send: bool, rows: u64) -> BTreeMap<String, String> {
        let rec = RecordingStream::disabled();
        let mut columns = SeriesColumns::default();
        columns.begin(&rec, plan()).unwrap();
        for flush in 0..2 {
            let steps: Vec<i64> = (0..rows).map(|i| (flush * rows + i) as i64).collect();
            let seconds: Vec<f64> = steps.iter().map(|&s| frame(s as u64).time).collect();
            for &s in &steps {
                columns.push(&frame(s as u64));
            }
            if send {
                columns.send(&rec, &steps, &seconds).unwrap();
            } else {
                columns.discard(&steps, &seconds);
            }
            assert!(columns.entities.iter().all(|e| e.values.is_empty()), "every hand-over empties the buffers");
        }
        columns.digests()
    }

    #[test]
    fn dropping_the_rows_continues_the_digests_as_sending_them_does() {
        let sent = digests_after(true, 5);
        assert_eq!(sent.len(), 3, "one digest per series: {sent:?}");
        assert_eq!(digests_after(false, 5), sent);
        // The digests do depend on the rows: fewer rows, other digests.
        assert!(digests_after(true, 4).values().zip(sent.values()).all(|(a, b)| a != b));
    }
}
