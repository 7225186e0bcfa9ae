//! What the spatial and space-time views draw for one frame, and the column buffers that carry
//! it to Rerun in explicit chunks (so the same frames always make the same chunks). Colours,
//! radii and draw order are static ([`log_styles`]) except the contact's, which shows its state.

use std::collections::BTreeMap;

use rerun::{LineStrips2D, SerializedComponentColumn};

use crate::frame::{Frame, Layout, SegmentSample};
use crate::record::colormap::{SLIP_RATE, sample};
use crate::record::schema::{self, RecordingPlan};
use crate::sink::slip_front::OPEN_COLOUR;
use crate::sink::spacetime::{TIME_BINS, map_height};

/// One entity's drawing for one frame: its strips, and their colours where they change from
/// frame to frame (else the entity's static style, [`log_styles`]).
struct Row {
    strips: Vec<Vec<[f32; 2]>>,
    colours: Option<Vec<[u8; 3]>>,
}

/// The fixed look of each geometry entity: colour (none for the contact, whose colours change
/// and would be hidden by a static one), radius in UI points, draw order.
const STYLES: [(&str, Option<[u8; 3]>, f32, f32); 5] = [
    (schema::SPATIAL_MESH, Some([150, 150, 150]), 0.75, 0.0),
    (schema::SPATIAL_CONTACT, None, 4.0, 10.0),
    (schema::SPATIAL_BASE, Some([90, 90, 90]), 1.5, 0.0),
    (schema::SPATIAL_SPRING, Some([200, 200, 200]), 1.0, 0.0),
    (schema::SPACETIME_NOW, Some([255, 255, 255]), 1.0, 10.0),
];

/// Logs the static look of every geometry entity, and the base of a block, which does not
/// move in the view (its displacement is a time series).
pub fn log_styles(rec: &rerun::RecordingStream, layout: &Layout) -> rerun::RecordingStreamResult<()> {
    for (entity, colour, radius, order) in STYLES {
        if entity == schema::SPATIAL_SPRING && layout.mesh.is_some() {
            continue;
        }
        let mut style =
            LineStrips2D::update_fields().with_radii([rerun::Radius::new_ui_points(radius)]).with_draw_order(order);
        if let Some([r, g, b]) = colour {
            style = style.with_colors([rerun::Color::from_rgb(r, g, b)]);
        }
        rec.log_static(entity, &style)?;
    }
    if let Some(mesh) = &layout.mesh {
        // 2D views point y down: the body is drawn with y negated.
        let bases = mesh.bases.iter().map(|line| line.iter().map(|&[x, y]| [x as f32, -y as f32]).collect::<Vec<_>>());
        rec.log_static(schema::SPATIAL_BASE, &LineStrips2D::new(bases))?;
    }
    Ok(())
}

/// Colour of a contact segment: blue while it sticks, orange to yellow as its slip rate grows
/// from 1× to 100× the event threshold, grey while it is open.
fn state_colour(segment: &SegmentSample, threshold: f64) -> [u8; 3] {
    let rate = segment.slip_rate;
    if segment.open {
        let [r, g, b, _] = OPEN_COLOUR.to_be_bytes();
        [r, g, b]
    } else if rate <= threshold {
        [70, 130, 200]
    } else {
        sample(&SLIP_RATE, 0.55 + 0.45 * ((rate / threshold).log10() / 2.0).clamp(0.0, 1.0))
    }
}

/// The drawing of `frame`: entity path and row, for every moving geometry entity of the scene.
fn draw(frame: &Frame, layout: &Layout, plan: &RecordingPlan) -> Vec<(&'static str, Row)> {
    let threshold = plan.slip_rate_threshold;
    let mag = plan.spec.magnification;
    let mut rows = Vec::new();
    if let Some(mesh) = &layout.mesh {
        // 2D views point y down: the body is drawn with y negated, above its base.
        let at = |k: u32| -> [f32; 2] {
            let ([x, y], [ux, uy]) = (mesh.nodes[k as usize], frame.mesh[k as usize]);
            [(x + mag * ux) as f32, -(y + mag * uy) as f32]
        };
        let lines = mesh.lines.iter().map(|line| line.iter().map(|&k| at(k)).collect()).collect();
        rows.push((schema::SPATIAL_MESH, Row { strips: lines, colours: None }));
        rows.push((
            schema::SPATIAL_CONTACT,
            Row {
                strips: mesh.contact.iter().map(|&[a, b]| vec![at(a), at(b)]).collect(),
                colours: Some(frame.segments.iter().map(|s| state_colour(s, threshold)).collect()),
            },
        ));
    } else if let Some([x, _]) = frame.block {
        // Spring-block: the block, its contact patch, and the spring to the moving far end.
        let left = (mag * x) as f32;
        let block = vec![[left, 0.0], [left + 1.0, 0.0], [left + 1.0, -0.6], [left, -0.6], [left, 0.0]];
        rows.push((schema::SPATIAL_MESH, Row { strips: vec![block], colours: None }));
        rows.push((
            schema::SPATIAL_CONTACT,
            Row {
                strips: vec![vec![[left, 0.0], [left + 1.0, 0.0]]],
                colours: Some(vec![state_colour(&frame.segments[0], threshold)]),
            },
        ));
        let far = 2.5 + (mag * frame.base_displacement) as f32;
        let start = left + 1.0;
        let coils = 8;
        let spring: Vec<[f32; 2]> = (0..=2 * coils)
            .map(|i| {
                let s = i as f32 / (2 * coils) as f32;
                let wiggle = if i == 0 || i == 2 * coils {
                    0.0
                } else if i % 2 == 0 {
                    0.1
                } else {
                    -0.1
                };
                [start + s * (far - start), -0.3 + wiggle]
            })
            .collect();
        rows.push((schema::SPATIAL_SPRING, Row { strips: vec![spring], colours: None }));
        rows.push((schema::SPATIAL_BASE, Row { strips: vec![vec![[-0.5, 0.05], [far + 0.5, 0.05]]], colours: None }));
    }
    // The space-time cursor: the current time's column across the map.
    let column = (frame.time / plan.t_end * TIME_BINS as f64) as f32;
    let height = map_height(layout.segments.len()) as f32;
    rows.push((schema::SPACETIME_NOW, Row { strips: vec![vec![[column, 0.0], [column, height]]], colours: None }));
    rows
}

/// Buffered rows of one entity's line strips.
#[derive(Default)]
struct Columns {
    strips: Vec<Vec<[f32; 2]>>,
    /// Colours per strip, for entities whose colours change.
    colours: Vec<rerun::Color>,
    /// Strips per row.
    lengths: Vec<usize>,
}

/// The geometry of recorded frames, buffered per entity.
#[derive(Default)]
pub struct GeometryBuffer {
    entities: BTreeMap<&'static str, Columns>,
    points: usize,
}

impl GeometryBuffer {
    /// Adds the drawing of `frame`.
    pub fn push(&mut self, frame: &Frame, layout: &Layout, plan: &RecordingPlan) {
        for (entity, row) in draw(frame, layout, plan) {
            let columns = self.entities.entry(entity).or_default();
            columns.lengths.push(row.strips.len());
            self.points += row.strips.iter().map(Vec::len).sum::<usize>();
            let colours = row.colours.into_iter().flatten();
            columns.colours.extend(colours.map(|[r, g, b]| rerun::Color::from_rgb(r, g, b)));
            columns.strips.extend(row.strips);
        }
    }

    /// Drops the buffered rows, sending nothing (a measuring build's hand-over,
    /// [`crate::sink::WITHOUT_RERUN`]).
    pub fn discard(&mut self) {
        self.entities.clear();
        self.points = 0;
    }

    /// Points buffered so far (the flush budget).
    pub fn points(&self) -> usize {
        self.points
    }

    /// Takes the buffered rows as component columns, entity by entity. The contact is drawn
    /// over the mesh.
    pub fn take(&mut self) -> Result<Vec<(&'static str, Vec<SerializedComponentColumn>)>, rerun::SerializationError> {
        self.points = 0;
        let mut out = Vec::with_capacity(self.entities.len());
        for (entity, columns) in std::mem::take(&mut self.entities) {
            let mut strips = LineStrips2D::new(columns.strips);
            if !columns.colours.is_empty() {
                strips = strips.with_colors(columns.colours);
            }
            out.push((entity, strips.columns(columns.lengths)?.collect()));
        }
        Ok(out)
    }
}
