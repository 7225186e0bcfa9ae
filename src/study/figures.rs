//! `slipfront figures`: PNG plots like the paper's Figures 8 and 9, from a recording.
//!
//! * `<case>_fig8_displacement.png`: horizontal displacement at the probe nodes and of the base.
//! * `<case>_fig9_traction_structure.png`: tangential traction and degree of structure `1/R*` at
//!   the probe segments.
//! * `<case>_spacetime.png`: slip rate of every recorded segment against position (across) and
//!   time (down), on a log colour scale: how ruptures nucleate and propagate.
//!
//! Probes are the case's named nodes and segments; without names, up to six recorded ones
//! spread along the surface. A body's contacts have their own figures,
//! `crate::study::contact_figures`.

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use crate::frame::Quantity;
use crate::frame::SceneKind;
use crate::inspect::{Recording, Series};
use crate::record::colormap::{POSITION, SLIP_RATE, sample};
use crate::record::schema::{self, RunInfo};

pub(crate) const WIDTH: u32 = 1400;
pub(crate) const HEIGHT: u32 = 800;

/// Registers the embedded DejaVu Sans as the plots' font (plotters' `ab_glyph` backend reads no
/// system fonts).
pub(crate) fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
            .unwrap_or_else(|_| panic!("the embedded DejaVu Sans is a valid font"));
    });
}

/// One line of a plot.
struct Line<'a> {
    label: String,
    series: &'a Series,
    colour: RGBColor,
}

/// Writes the figures of Figures 8 and 9 and the space-time map into `out`; returns their paths.
pub fn write_figures(recording: &Recording, out: &Path) -> Result<Vec<PathBuf>, String> {
    register_font();
    let info: RunInfo = recording
        .static_texts
        .get(schema::RUN_INFO)
        .ok_or("the recording has no run description (slipfront/run)")
        .and_then(|t| toml::from_str(t).map_err(|_| "the run description is unreadable"))?;
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let end = data_end(recording, info.t_end);
    let colour = |position: usize, count: usize| {
        let [r, g, b] = sample(&POSITION, if count > 1 { position as f64 / (count - 1) as f64 } else { 0.5 });
        RGBColor(r, g, b)
    };
    let pick = |recorded: &[usize], probes: &[usize]| -> Vec<usize> {
        if !probes.is_empty() {
            return recorded.iter().enumerate().filter(|(_, k)| probes.contains(k)).map(|(i, _)| i).collect();
        }
        let n = recorded.len();
        if n <= 6 { (0..n).collect() } else { (0..6).map(|i| i * (n - 1) / 5).collect() }
    };

    // Figure 8: displacements.
    let mut displacement = Vec::new();
    let nodes = pick(&info.recorded_nodes, &info.probe_nodes);
    for (rank, &i) in nodes.iter().enumerate() {
        if let Some(series) = recording.series.get(&schema::instance_series(schema::node_entity(0), i)) {
            displacement.push(Line { label: info.node_labels[i].clone(), series, colour: colour(rank, nodes.len()) });
        }
    }
    if let Some(series) = recording.series.get(schema::BLOCK_X) {
        displacement.push(Line { label: "block".into(), series, colour: colour(0, 1) });
    }
    if let Some(series) = recording.series.get(schema::BASE_UX) {
        let label = if info.kind == SceneKind::SpringBlock { "spring end" } else { "base" };
        displacement.push(Line { label: label.into(), series, colour: RGBColor(120, 120, 120) });
    }
    let fig8 = out.join(format!("{}_fig8_displacement.png", info.case));
    plot(&fig8, &[(&format!("{}: horizontal displacement", info.case), "u_x (m)", &displacement)], end)?;

    // Figure 9: traction and degree of structure at the probe segments.
    let segments = pick(&info.recorded_segments, &info.probe_segments);
    let lines_for = |q: Quantity| -> Vec<Line<'_>> {
        segments
            .iter()
            .enumerate()
            .filter_map(|(rank, &i)| {
                recording.series.get(&schema::instance_series(&schema::segment_entity(q), i)).map(|series| Line {
                    label: info.segment_labels[i].clone(),
                    series,
                    colour: colour(rank, segments.len()),
                })
            })
            .collect()
    };
    let traction = lines_for(Quantity::TractionT);
    let structure = lines_for(Quantity::Structure);
    let fig9 = out.join(format!("{}_fig9_traction_structure.png", info.case));
    plot(
        &fig9,
        &[
            (&format!("{}: tangential traction", info.case), "f_t (Pa)", &traction),
            ("degree of structure", "1/R*", &structure),
        ],
        end,
    )?;
    let spacetime = out.join(format!("{}_spacetime.png", info.case));
    let rates: Vec<(f64, &Series)> = info
        .recorded_segments
        .iter()
        .enumerate()
        .filter_map(|(i, &k)| {
            recording
                .series
                .get(&schema::instance_series(&schema::segment_entity(Quantity::SlipRate), i))
                .map(|s| (k as f64, s))
        })
        .collect();
    let mut written = vec![fig8, fig9];
    if !rates.is_empty() {
        plot_spacetime(&spacetime, &info, &rates, end)?;
        written.push(spacetime);
    }
    Ok(written)
}

/// The end of the recorded span (s): where `--at` times must lie.
pub fn recorded_end(recording: &Recording) -> f64 {
    let t_end = recording
        .static_texts
        .get(schema::RUN_INFO)
        .and_then(|t| toml::from_str::<RunInfo>(t).ok())
        .map_or(0.0, |info| info.t_end);
    data_end(recording, t_end)
}

/// The time axes' end: the last recorded time of any series (a run interrupted or failed ends
/// before `t_end`), or `t_end` where nothing past 0 was recorded.
fn data_end(recording: &Recording, t_end: f64) -> f64 {
    let last = recording.series.values().filter_map(|s| s.times.last().copied()).fold(0.0_f64, f64::max);
    if last > 0.0 { last } else { t_end }
}

/// A tick label with as many decimals as ticks `step` apart need to read differently
/// (`1.4998`, `1.4999`, `1.5000` rather than `1.5` three times).
pub(crate) fn tick_label(value: f64, step: f64) -> String {
    // A step of 9.99999e-6 (a tenth of a span in floating point) is one of 1e-5.
    let decimals = if step > 0.0 && step.is_finite() { (-(step.log10() + 1e-6).floor()).max(0.0) as usize } else { 0 };
    format!("{value:.decimals$}")
}

/// Slip rate against segment (across) and time (down), log colours from a hundredth of the
/// event threshold to the peak.
fn plot_spacetime(path: &Path, info: &RunInfo, rates: &[(f64, &Series)], end: f64) -> Result<(), String> {
    let floor = info.slip_rate_threshold / 100.0;
    let peak = rates.iter().flat_map(|(_, s)| s.values.iter().copied()).fold(0.0_f64, f64::max);
    let top = peak.max(info.slip_rate_threshold * 10.0);
    let segments = info.segments as f64;
    let mut pixels = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!("{}: slip rate, black {floor:.1e} m/s to yellow {top:.1e} m/s (log)", info.case),
                ("sans-serif", 24),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(0.0..segments, end..0.0)
            .map_err(draw_error)?;
        chart
            .configure_mesh()
            .x_desc("segment (from the left)")
            .y_desc("time (s)")
            .label_style(("sans-serif", 16))
            .disable_mesh()
            .draw()
            .map_err(draw_error)?;
        for (k, series) in rates {
            let cells = series.times.windows(2).zip(&series.values[1..]).map(|(t, &rate)| {
                let x =
                    if rate <= floor { 0.0 } else { ((rate / floor).log10() / (top / floor).log10()).clamp(0.0, 1.0) };
                let [r, g, b] = sample(&SLIP_RATE, x);
                Rectangle::new([(*k, t[0]), (k + 1.0, t[1])], RGBColor(r, g, b).filled())
            });
            chart.draw_series(cells).map_err(draw_error)?;
        }
        root.present().map_err(draw_error)?;
    }
    write_png(path, &pixels)
}

/// Draws stacked panels of lines against time and writes a PNG.
fn plot(path: &Path, panels: &[(&str, &str, &Vec<Line<'_>>)], t_end: f64) -> Result<(), String> {
    let mut pixels = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let areas = root.split_evenly((panels.len(), 1));
        for ((title, unit, lines), area) in panels.iter().zip(areas) {
            let (lo, hi) = lines
                .iter()
                .flat_map(|l| l.series.values.iter().copied().filter(|v| v.is_finite()))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
            let (lo, hi) = if lo.is_finite() && hi > lo { (lo, hi) } else { (lo.min(0.0) - 1.0, hi.max(0.0) + 1.0) };
            let pad = 0.05 * (hi - lo);
            let mut chart = ChartBuilder::on(&area)
                .caption(*title, ("sans-serif", 24))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(80)
                .build_cartesian_2d(0.0..t_end, (lo - pad)..(hi + pad))
                .map_err(draw_error)?;
            // plotters draws about ten labels per axis: label them by a tenth of the span.
            let (x_step, y_step) = (t_end / 10.0, (hi - lo + 2.0 * pad) / 10.0);
            chart
                .configure_mesh()
                .x_desc("time (s)")
                .y_desc(*unit)
                .x_label_formatter(&|v| tick_label(*v, x_step))
                .y_label_formatter(&|v| tick_label(*v, y_step))
                .label_style(("sans-serif", 16))
                .draw()
                .map_err(draw_error)?;
            let curves = lines.iter().map(|line| {
                let points = line.series.times.iter().copied().zip(line.series.values.iter().copied());
                (line.label.clone(), line.colour, points)
            });
            draw_lines(&mut chart, curves, SeriesLabelPosition::UpperLeft, 16)?;
        }
        root.present().map_err(draw_error)?;
    }
    write_png(path, &pixels)
}

/// A chart of `f64` against `f64` on a bitmap (`'a` its drawing area's, `'b` its pixels').
pub(crate) type Chart<'a, 'b> = ChartContext<'a, BitMapBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draws each `(label, colour, points)` as a line on `chart`, and their legend at `position` in
/// `font_size` points.
pub(crate) fn draw_lines<'a, 'b: 'a, P: Iterator<Item = (f64, f64)>>(
    chart: &mut Chart<'a, 'b>,
    lines: impl IntoIterator<Item = (String, RGBColor, P)>,
    position: SeriesLabelPosition,
    font_size: u32,
) -> Result<(), String> {
    for (label, colour, points) in lines {
        chart
            .draw_series(LineSeries::new(points, colour.stroke_width(2)))
            .map_err(draw_error)?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(3)));
    }
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", font_size))
        .draw()
        .map_err(draw_error)
}

pub(crate) fn write_png(path: &Path, pixels: &[u8]) -> Result<(), String> {
    let file = std::fs::File::create(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), WIDTH, HEIGHT);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    writer.write_image_data(pixels).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    writer.finish().map_err(|e| format!("cannot write {}: {e}", path.display()))
}

pub(crate) fn draw_error(e: impl std::fmt::Display) -> String {
    format!("cannot draw the figure: {e}")
}

/// One curve of a work-precision plot: `(wall time s, error)` points in order of effort.
pub struct WorkPrecisionCurve {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// A logarithmic axis labelled at 1, 2 and 5 times powers of ten only: plotters labels every
/// mesh line, which crowds an axis spanning less than a decade.
fn log_label(value: f64, scientific: bool) -> String {
    let exponent = value.log10().floor() as i32;
    let mantissa = value / 10f64.powi(exponent);
    match [1.0, 2.0, 5.0, 10.0].iter().find(|m| (mantissa / *m - 1.0).abs() < 1e-6) {
        Some(&m) if scientific => {
            let (m, e) = if m == 10.0 { (1.0, exponent + 1) } else { (m, exponent) };
            format!("{m}e{e}")
        }
        Some(&m) => format!("{}", m * 10f64.powi(exponent)),
        None => String::new(),
    }
}

/// Writes a log-log plot of error against wall time, one panel per `(title, curves)`.
pub fn plot_work_precision(path: &Path, panels: &[(String, Vec<WorkPrecisionCurve>)]) -> Result<(), String> {
    register_font();
    const COLOURS: [RGBColor; 6] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(148, 103, 189),
        RGBColor(255, 127, 14),
        RGBColor(23, 190, 207),
    ];
    let mut pixels = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let areas = root.split_evenly((1, panels.len().max(1)));
        for ((title, curves), area) in panels.iter().zip(areas) {
            let finite = |p: &&(f64, f64)| p.0 > 0.0 && p.1 > 0.0 && p.0.is_finite() && p.1.is_finite();
            let all: Vec<(f64, f64)> = curves.iter().flat_map(|c| c.points.iter().filter(finite).copied()).collect();
            let range = |values: &mut dyn Iterator<Item = f64>| {
                let (lo, hi) = values.fold((f64::INFINITY, 0.0_f64), |(a, b), v| (a.min(v), b.max(v)));
                if lo.is_finite() && hi > lo { (lo / 2.0, hi * 2.0) } else { (1e-3, 1.0) }
            };
            let (x0, x1) = range(&mut all.iter().map(|p| p.0));
            let (y0, y1) = range(&mut all.iter().map(|p| p.1));
            let mut chart = ChartBuilder::on(&area)
                .caption(title.as_str(), ("sans-serif", 22))
                .margin(12)
                .x_label_area_size(45)
                .y_label_area_size(80)
                .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
                .map_err(draw_error)?;
            chart
                .configure_mesh()
                .x_desc("wall time (s), median")
                .y_desc("relative error")
                .x_label_formatter(&|v| log_label(*v, false))
                .y_label_formatter(&|v| log_label(*v, true))
                .label_style(("sans-serif", 15))
                .draw()
                .map_err(draw_error)?;
            for (i, curve) in curves.iter().enumerate() {
                let colour = COLOURS[i % COLOURS.len()];
                let points: Vec<(f64, f64)> = curve.points.iter().filter(finite).copied().collect();
                chart
                    .draw_series(LineSeries::new(points.iter().copied(), colour.stroke_width(2)))
                    .map_err(draw_error)?
                    .label(curve.label.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(3)));
                chart.draw_series(points.iter().map(|&p| Circle::new(p, 4, colour.filled()))).map_err(draw_error)?;
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .label_font(("sans-serif", 14))
                .draw()
                .map_err(draw_error)?;
        }
        root.present().map_err(draw_error)?;
    }
    write_png(path, &pixels)
}

/// One series of a proportions plot: per row, how many of how many runs hold.
pub struct Proportions {
    pub label: String,
    pub counts: Vec<(usize, usize)>,
}

/// Writes proportions per row with their Wilson 95 % intervals (`interval`), one colour per
/// series, side by side within each row; the x axis is named `axis.0` and row `i` labelled
/// `axis.1[i]` (every k-th row where the labels would overlap).
pub fn plot_proportions(
    path: &Path,
    title: &str,
    axis: (&str, &[String]),
    series: &[Proportions],
    interval: fn(usize, usize) -> (f64, f64),
) -> Result<(), String> {
    register_font();
    const COLOURS: [RGBColor; 4] =
        [RGBColor(31, 119, 180), RGBColor(214, 39, 40), RGBColor(44, 160, 44), RGBColor(40, 40, 40)];
    let mut pixels = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_error)?;
        let (name, labels) = axis;
        let rows = labels.len();
        let every = label_stride(labels, WIDTH - 2 * 16 - 70);
        let labelled: Vec<f64> = (0..rows).step_by(every).map(|row| row as f64).collect();
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 22))
            .margin(16)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(RowAxis { rows, labelled }, 0.0..1.0)
            .map_err(draw_error)?;
        chart
            .configure_mesh()
            .x_desc(name)
            .y_desc("share of members")
            .x_label_formatter(&|v| labels.get(v.round() as usize).cloned().unwrap_or_default())
            .label_style(("sans-serif", 15))
            .draw()
            .map_err(draw_error)?;
        let width = 0.7 / series.len().max(1) as f64;
        for (i, s) in series.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            let offset = (i as f64 - (series.len() as f64 - 1.0) / 2.0) * width;
            let rows: Vec<(f64, f64, f64, f64)> = s
                .counts
                .iter()
                .enumerate()
                .filter(|(_, (_, n))| *n > 0)
                .map(|(row, &(held, n))| {
                    let (lo, hi) = interval(held, n);
                    (row as f64 + offset, lo, held as f64 / n as f64, hi)
                })
                .collect();
            // The interval as a vertical line, the share as a dot on it.
            chart
                .draw_series(
                    rows.iter().map(|&(x, lo, _, hi)| PathElement::new(vec![(x, lo), (x, hi)], colour.stroke_width(2))),
                )
                .map_err(draw_error)?;
            chart
                .draw_series(rows.iter().map(|&(x, _, share, _)| Circle::new((x, share), 5, colour.filled())))
                .map_err(draw_error)?
                .label(s.label.clone())
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, colour.filled()));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 15))
            .draw()
            .map_err(draw_error)?;
        root.present().map_err(draw_error)?;
    }
    write_png(path, &pixels)
}

/// An x axis of rows `0, 1, …` (row `i` spans `i ± 0.5`), ticked at the rows `labelled` only.
struct RowAxis {
    rows: usize,
    labelled: Vec<f64>,
}

impl Ranged for RowAxis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        RangedCoordf64::from(self.range()).map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() { Vec::new() } else { self.labelled.clone() }
    }

    fn range(&self) -> std::ops::Range<f64> {
        -0.5..(self.rows as f64 - 0.5)
    }
}

/// Every how many rows a label fits: the widest label at the axis' font, plus a gap of 8 px,
/// over `width` px of axis.
fn label_stride(labels: &[String], width: u32) -> usize {
    register_font();
    let font: FontDesc<'_> = ("sans-serif", 15).into_font();
    let widest = labels.iter().map(|l| font.box_size(l).map_or(0, |(w, _)| w)).max().unwrap_or(0);
    let widest = f64::from(widest) + 8.0;
    let per_row = f64::from(width) / labels.len().max(1) as f64;
    ((widest / per_row).ceil() as usize).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn proportions_png(labels: &[String], name: &str) -> Vec<u8> {
        let path = std::env::temp_dir().join(format!("slipfront-proportions-{name}-{}.png", std::process::id()));
        let series = [Proportions { label: "1. left end".into(), counts: vec![(1, 2); labels.len()] }];
        plot_proportions(&path, "t", ("scene.normal_traction.left (Pa)", labels), &series, |_, _| (0.2, 0.8)).unwrap();
        let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
        let mut reader = decoder.read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
        reader.next_frame(&mut pixels).unwrap();
        std::fs::remove_file(&path).unwrap();
        pixels
    }

    #[test]
    fn rows_are_labelled_by_their_values_below_the_plot() {
        let values: Vec<String> = ["300", "350"].map(String::from).to_vec();
        let others: Vec<String> = ["1e3", "2e3"].map(String::from).to_vec();
        let (a, b) = (proportions_png(&values, "a"), proportions_png(&others, "b"));
        let row = (WIDTH * 3) as usize;
        let band = (HEIGHT - 16 - 45) as usize * row;
        assert_eq!(a[..band], b[..band], "the plot above the axis' labels is the same");
        assert_ne!(a[band..], b[band..], "the labels below the axis are the rows' own");
    }

    #[test]
    fn labels_too_wide_for_every_row_are_thinned() {
        register_font();
        let labels = |n: usize| vec!["350/1200".to_string(); n];
        let (width, _) = ("sans-serif", 15).into_font().box_size("350/1200").unwrap();
        assert!((50..66).contains(&width), "{width} px");
        assert_eq!(label_stride(&labels(2), 1298), 1);
        assert_eq!(label_stride(&labels(18), 1298), 1, "the shipped sweep's 18 rows, 72 px apart");
        assert_eq!(label_stride(&labels(40), 1298), 3, "32 px apart");
    }

    #[test]
    fn the_time_axis_ends_where_an_interrupted_runs_data_ends() {
        let mut recording = Recording::default();
        let series = Series { steps: vec![0, 1, 2], times: vec![0.0, 10.0, 42.5], values: vec![0.0; 3] };
        recording.series.insert("contact/friction_force".into(), series);
        assert_eq!(data_end(&recording, 1000.0), 42.5);
        assert_eq!(data_end(&Recording::default(), 1000.0), 1000.0, "nothing recorded: the planned end");
    }

    #[test]
    fn ticks_over_a_narrow_span_read_differently() {
        // 1/R* of an interrupted run: 1.49990 to 1.5, ticks 1e-5 apart.
        let (lo, hi) = (1.4999, 1.5);
        let step = (hi - lo) / 10.0;
        let labels: Vec<String> = (0..=10).map(|i| tick_label(lo + i as f64 * step, step)).collect();
        let distinct: std::collections::BTreeSet<&String> = labels.iter().collect();
        assert_eq!(distinct.len(), labels.len(), "{labels:?}");
        assert_eq!(labels[0], "1.49990");
        assert_eq!(tick_label(400.0, 100.0), "400");
    }
}
