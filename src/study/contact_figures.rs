//! `slipfront figures` for a body's contacts: the force–displacement curve of the drive, and
//! profiles along the contacts' arc length at chosen times.
//!
//! * `<case>_force_displacement.png`: the total friction force `Σ w f_t` against the
//!   displacement of the (first) contact's main body along its drive, both taken positive in
//!   the first loading: a pile's pull-out curve, with its static peak, the drop to kinetic
//!   friction, the hold and the reversal.
//! * `<case>_profiles.png`: the tangential traction `f_t`, the slip rate (log scale) and the
//!   degree of structure `1/R*` of every recorded segment against its arc length, one line per
//!   chosen time (the last recorded row at or before it): how a slip front runs along the
//!   contact. A body of several contacts has a line per contact and time.

use std::path::{Path, PathBuf};

use plotters::prelude::*;

use crate::frame::Quantity;
use crate::inspect::{Recording, Series};
use crate::record::colormap::{POSITION, sample};
use crate::record::schema::{self, RunInfo};
use crate::study::figures::{
    HEIGHT, WIDTH, draw_error, draw_lines, recorded_end, register_font, tick_label, write_png,
};

/// One curve of an xy panel.
struct Curve {
    label: String,
    colour: RGBColor,
    points: Vec<(f64, f64)>,
}

/// One panel: its title, the axes' descriptions, its curves.
struct Panel {
    title: String,
    x: String,
    y: String,
    curves: Vec<Curve>,
}

/// The default times of the profiles: a quarter, half, three quarters and all of the recorded
/// span.
pub fn default_times(end: f64) -> Vec<f64> {
    [0.25, 0.5, 0.75, 1.0].iter().map(|f| f * end).collect()
}

/// Draws both figures of a body's recording into `out`, the profiles at `times` (s; empty: a
/// quarter, half, three quarters and the end of the recorded span); nothing for a point or
/// spring block, or a recording without the series they need. Returns their paths.
pub fn write(recording: &Recording, out: &Path, times: &[f64]) -> Result<Vec<PathBuf>, String> {
    let Some(info) = recording.static_texts.get(schema::RUN_INFO).and_then(|t| toml::from_str::<RunInfo>(t).ok())
    else {
        return Ok(Vec::new());
    };
    if !info.kind.has_body() {
        return Ok(Vec::new());
    }
    register_font();
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let times = if times.is_empty() { default_times(recorded_end(recording)) } else { times.to_vec() };
    let info = &info;
    let mut written = Vec::new();
    if let (Some(force), Some(drive)) =
        (recording.series.get(schema::FRICTION_FORCE), recording.series.get(schema::BASE_UX))
    {
        let path = out.join(format!("{}_force_displacement.png", info.case));
        plot_xy(&path, &[force_displacement(info, force, drive)])?;
        written.push(path);
    }
    if info.segment_centres.len() == info.recorded_segments.len() && info.segment_centres.len() > 1 {
        let path = out.join(format!("{}_profiles.png", info.case));
        plot_xy(&path, &profiles(recording, info, &times))?;
        written.push(path);
    }
    Ok(written)
}

/// The friction force against the drive's displacement, each signed so that the first loading
/// is positive (the sign of a force along the contact's own tangent depends on which way the
/// contact runs around the body).
fn force_displacement(info: &RunInfo, force: &Series, drive: &Series) -> Panel {
    let largest = force.values.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    let sign_of =
        |values: &[f64], scale: f64| values.iter().find(|v| v.abs() > 0.01 * scale).map_or(1.0, |v| v.signum());
    let reach = drive.values.iter().fold(0.0_f64, |m, u| m.max(u.abs()));
    let (f_sign, u_sign) = (sign_of(&force.values, largest), sign_of(&drive.values, reach));
    let points = drive.values.iter().zip(&force.values).map(|(u, f)| (u_sign * u, f_sign * f)).collect();
    Panel {
        title: format!("{}: friction force against the main body's displacement", info.case),
        x: "displacement along the drive, positive in the first loading (m)".into(),
        y: format!("friction force ({}), positive in the first loading", info.force_unit()),
        curves: vec![Curve { label: "Σ w f_t".into(), colour: RGBColor(31, 119, 180), points }],
    }
}

/// Profiles of `f_t`, slip rate and `1/R*` along the arc length at `times`.
fn profiles(recording: &Recording, info: &RunInfo, times: &[f64]) -> Vec<Panel> {
    let floor = info.slip_rate_threshold / 100.0;
    let quantities = [
        (Quantity::TractionT, "tangential traction", "f_t (Pa)"),
        (
            Quantity::SlipRate,
            "slip rate (log10 of m/s, floored at a hundredth of the event threshold)",
            "log10 slip rate",
        ),
        (Quantity::Structure, "degree of structure", "1/R*"),
    ];
    // Where the arc length falls back, another contact begins.
    let mut contacts: Vec<Vec<usize>> = Vec::new();
    for (i, s) in info.segment_centres.iter().enumerate() {
        match contacts.last_mut() {
            Some(run) if info.segment_centres[*run.last().expect("runs are not empty")] < *s => run.push(i),
            _ => contacts.push(vec![i]),
        }
    }
    quantities
        .iter()
        .map(|&(q, title, unit)| {
            let mut curves = Vec::new();
            for (rank, &t) in times.iter().enumerate() {
                let [r, g, b] =
                    sample(&POSITION, if times.len() > 1 { rank as f64 / (times.len() - 1) as f64 } else { 0.5 });
                for (c, run) in contacts.iter().enumerate() {
                    let points: Vec<(f64, f64)> = run
                        .iter()
                        .filter_map(|&i| {
                            let series =
                                recording.series.get(&schema::instance_series(&schema::segment_entity(q), i))?;
                            let (_, v) = series.at(t)?;
                            let v = if q == Quantity::SlipRate { v.max(floor).log10() } else { v };
                            Some((info.segment_centres[i], v))
                        })
                        .collect();
                    let label = if contacts.len() > 1 {
                        format!(
                            "t = {t} s, {}",
                            info.contacts.get(c).cloned().unwrap_or_else(|| format!("contact {c}"))
                        )
                    } else {
                        format!("t = {t} s")
                    };
                    if !points.is_empty() {
                        curves.push(Curve { label, colour: RGBColor(r, g, b), points });
                    }
                }
            }
            Panel {
                title: format!("{}: {title}", info.case),
                x: "arc length along the contact (m)".into(),
                y: unit.into(),
                curves,
            }
        })
        .collect()
}

/// Stacked panels of xy curves, written as a PNG.
fn plot_xy(path: &Path, panels: &[Panel]) -> Result<(), String> {
    let mut pixels = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let areas = root.split_evenly((panels.len(), 1));
        for (panel, area) in panels.iter().zip(areas) {
            let range = |pick: &dyn Fn(&(f64, f64)) -> f64| {
                let (lo, hi) = panel
                    .curves
                    .iter()
                    .flat_map(|c| c.points.iter().map(pick).filter(|v| v.is_finite()))
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
                // A span within a millionth of the values' size is rounding (a flat 1/R* of 1
                // with dips of an ulp): the panel then shows a tenth of that size either side.
                let size = lo.abs().max(hi.abs());
                let (lo, hi) = if lo.is_finite() && hi - lo > 1e-6 * size {
                    (lo, hi)
                } else if lo.is_finite() && size > 0.0 {
                    (0.5 * (lo + hi) - 0.1 * size, 0.5 * (lo + hi) + 0.1 * size)
                } else {
                    (lo.min(0.0) - 1.0, hi.max(0.0) + 1.0)
                };
                let pad = 0.05 * (hi - lo);
                (lo - pad, hi + pad)
            };
            let ((x0, x1), (y0, y1)) = (range(&|p| p.0), range(&|p| p.1));
            let mut chart = ChartBuilder::on(&area)
                .caption(&panel.title, ("sans-serif", 22))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(90)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(draw_error)?;
            let (x_step, y_step) = ((x1 - x0) / 10.0, (y1 - y0) / 10.0);
            chart
                .configure_mesh()
                .x_desc(&panel.x)
                .y_desc(&panel.y)
                .x_label_formatter(&|v| tick_label(*v, x_step))
                .y_label_formatter(&|v| tick_label(*v, y_step))
                .label_style(("sans-serif", 16))
                .draw()
                .map_err(draw_error)?;
            let curves = panel.curves.iter().map(|c| (c.label.clone(), c.colour, c.points.iter().copied()));
            draw_lines(&mut chart, curves, SeriesLabelPosition::UpperRight, 14)?;
        }
        root.present().map_err(draw_error)?;
    }
    write_png(path, &pixels)
}
