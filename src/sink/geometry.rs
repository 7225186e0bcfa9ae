//! What the spatial and space-time views draw for one frame, and the column buffers that carry
//! it to Rerun in explicit chunks (so the same frames always make the same chunks).

use std::collections::BTreeMap;

use rerun::{LineStrips2D, SerializedComponentColumn};

use crate::frame::{Frame, Layout};
use crate::record::colormap::{SLIP_RATE, sample};
use crate::record::schema::{self, RecordingPlan};

/// Rows of the space-time image, spread over `[0, t_end]`.
pub const SPACETIME_ROWS: usize = 1000;
/// Target width of the space-time image (px); each segment gets an equal share.
pub const SPACETIME_WIDTH: usize = 500;

/// Width of the space-time image for `segments` segments (px).
pub fn spacetime_width(segments: usize) -> usize {
    let segments = segments.max(1);
    segments * (SPACETIME_WIDTH / segments).max(1)
}

/// One entity's drawing for one frame: strips with a colour and radius each.
struct Row {
    strips: Vec<Vec<[f32; 2]>>,
    colours: Vec<[u8; 3]>,
    /// Radius in UI points, for every strip of the row.
    radius: f32,
}

/// Colour of a contact segment: blue while it sticks, orange to yellow as its slip rate grows
/// from 1× to 100× the event threshold.
fn state_colour(rate: f64, threshold: f64) -> [u8; 3] {
    if rate <= threshold {
        [70, 130, 200]
    } else {
        sample(&SLIP_RATE, 0.55 + 0.45 * ((rate / threshold).log10() / 2.0).clamp(0.0, 1.0))
    }
}

/// The drawing of `frame`: entity path and row, for every geometry entity of the scene.
fn draw(frame: &Frame, layout: &Layout, plan: &RecordingPlan) -> Vec<(&'static str, Row)> {
    let threshold = plan.slip_rate_threshold;
    let mag = plan.spec.magnification;
    let grey = [150, 150, 150];
    let mut rows = Vec::new();
    if let Some(mesh) = layout.mesh {
        let (dx, dy) = (mesh.dx(), mesh.dy());
        // 2D views point y down: the block is drawn at negative y, above its base.
        let at = |i: usize, j: usize| -> [f32; 2] {
            let [ux, uy] = frame.mesh[mesh.node(i, j)];
            [(i as f64 * dx + mag * ux) as f32, -(j as f64 * dy + mag * uy) as f32]
        };
        let mut lines: Vec<Vec<[f32; 2]>> = (0..=mesh.ny).map(|j| (0..=mesh.nx).map(|i| at(i, j)).collect()).collect();
        lines.extend((0..=mesh.nx).map(|i| (0..=mesh.ny).map(|j| at(i, j)).collect()));
        let n = lines.len();
        rows.push((schema::SPATIAL_MESH, Row { strips: lines, colours: vec![grey; n], radius: 0.75 }));
        rows.push((
            schema::SPATIAL_CONTACT,
            Row {
                strips: (0..mesh.nx).map(|k| vec![at(k, 0), at(k + 1, 0)]).collect(),
                colours: frame.segments.iter().map(|s| state_colour(s.slip_rate, threshold)).collect(),
                radius: 4.0,
            },
        ));
        // The base: a line below the block with ticks that move with it.
        let y = (0.12 * mesh.height.min(mesh.width)) as f32;
        let shift = (mag * frame.base_displacement).rem_euclid(dx);
        let mut base = vec![vec![[0.0, y], [mesh.width as f32, y]]];
        base.extend((0..mesh.nx).map(|k| {
            let x = (k as f64 * dx + shift) as f32;
            vec![[x, y], [x, 2.0 * y]]
        }));
        let n = base.len();
        rows.push((schema::SPATIAL_BASE, Row { strips: base, colours: vec![[90, 90, 90]; n], radius: 1.5 }));
    } else if let Some([x, _]) = frame.block {
        // Spring-block: the block, its contact patch, and the spring to the moving far end.
        let left = (mag * x) as f32;
        let block = vec![[left, 0.0], [left + 1.0, 0.0], [left + 1.0, -0.6], [left, -0.6], [left, 0.0]];
        rows.push((schema::SPATIAL_MESH, Row { strips: vec![block], colours: vec![grey], radius: 0.75 }));
        rows.push((
            schema::SPATIAL_CONTACT,
            Row {
                strips: vec![vec![[left, 0.0], [left + 1.0, 0.0]]],
                colours: vec![state_colour(frame.segments[0].slip_rate, threshold)],
                radius: 4.0,
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
        rows.push((schema::SPATIAL_SPRING, Row { strips: vec![spring], colours: vec![[200, 200, 200]], radius: 1.0 }));
        rows.push((
            schema::SPATIAL_BASE,
            Row { strips: vec![vec![[-0.5, 0.05], [far + 0.5, 0.05]]], colours: vec![[90, 90, 90]], radius: 1.5 },
        ));
    }
    // The space-time cursor: the current time's row across the image.
    let width = spacetime_width(layout.segments.len()) as f32;
    let row = (frame.time / plan.t_end * SPACETIME_ROWS as f64) as f32;
    rows.push((
        schema::SPACETIME_NOW,
        Row { strips: vec![vec![[0.0, row], [width, row]]], colours: vec![[255, 255, 255]], radius: 1.0 },
    ));
    rows
}

/// Buffered rows of one entity's line strips.
#[derive(Default)]
struct Columns {
    strips: Vec<Vec<[f32; 2]>>,
    colours: Vec<rerun::Color>,
    radii: Vec<rerun::Radius>,
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
            columns.radii.extend(std::iter::repeat_n(rerun::Radius::new_ui_points(row.radius), row.strips.len()));
            columns.colours.extend(row.colours.iter().map(|[r, g, b]| rerun::Color::from_rgb(*r, *g, *b)));
            columns.strips.extend(row.strips);
        }
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
            let rows = columns.lengths.len();
            let mut serialized: Vec<SerializedComponentColumn> = LineStrips2D::new(columns.strips)
                .with_colors(columns.colours)
                .with_radii(columns.radii)
                .columns(columns.lengths)?
                .collect();
            let order = if entity == schema::SPATIAL_CONTACT { 10.0_f32 } else { 0.0 };
            serialized.extend(
                LineStrips2D::update_fields()
                    .with_many_draw_order(std::iter::repeat_n(order, rows))
                    .columns_of_unit_batches()?,
            );
            out.push((entity, serialized));
        }
        Ok(out)
    }
}
