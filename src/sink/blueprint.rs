//! The default blueprint sent with every recording, laid out to open on the answer:
//!
//! * top: the block with its contact coloured by state, and the profiles along x at the
//!   playhead (traction against strength, slip rate, `1/R*`);
//! * middle: the stick/slip lanes of the segments and the space-time map of slip rate, both
//!   with time across, so a rupture front reads the same in both;
//! * bottom: time series at the probes over the whole run (the paper's Figures 8 and 9) and the
//!   event log.
//!
//! Rerun 0.36's Rust blueprint API builds containers, views, their contents and per-entity
//! overrides, but not a view's properties (time axis, legend); [`send`] adds those to the same
//! blueprint store as the archetypes the viewer reads (`view/{id}/TimeAxis`,
//! `view/{id}/PlotLegend`).

use rerun::blueprint::components::PanelState;
use rerun::blueprint::{
    BarChartView, Blueprint, BlueprintActivation, BlueprintPanel, ContainerLike, Horizontal, SelectionPanel,
    Spatial2DView, StateTimelineView, Tabs, TextLogView, TimePanel, TimeSeriesView, Vertical,
    VisualizableArchetype as _,
};
use rerun::external::re_log_types::{BlueprintActivationCommand, LogMsg};
use rerun::external::re_sdk_types::blueprint::archetypes::{PlotLegend, TimeAxis};
use rerun::external::re_sdk_types::blueprint::components::{Corner2D, LinkAxis};
use rerun::external::re_sdk_types::datatypes::{TimeInt, TimeRange, TimeRangeBoundary};
use rerun::{AsComponents, RecordingStream, RecordingStreamBuilder, SeriesLines};

use crate::frame::Quantity;
use crate::frame::{Layout, SceneKind};
use crate::record::schema;
use crate::sink::collected;

/// Names of the views, for readers that check them.
pub const VIEW_BLOCK: &str = "Block";
pub const VIEW_STRENGTH: &str = "Along x (m): f_t against static and kinetic strength (Pa)";
/// The start of the slip-rate profile's name; the rest names its scale's floor.
pub const VIEW_SLIP_RATE: &str = "Along x (m): slip rate, log10(v / v0)";
pub const VIEW_STRUCTURE_PROFILE: &str = "Along x (m): 1/R*";
pub const VIEW_STATE: &str = "Stick (blue) / slip (orange), a lane per segment from x = 0 at the top";
pub const VIEW_SPACETIME: &str = "Space-time: log10 slip rate (m/s), x down, sim_time across";
pub const VIEW_TRACTION: &str = "Tangential traction f_t (Pa)";
pub const VIEW_STRUCTURE: &str = "Degree of structure 1/R*";
pub const VIEW_DISPLACEMENT: &str = "Displacement u_x (m)";
pub const VIEW_EVENTS: &str = "Slip events";

/// What the blueprint shows of a run.
pub struct Contents<'a> {
    pub layout: &'a Layout,
    /// Recorded segments and nodes (the instances of the series entities).
    pub segments: &'a [usize],
    pub nodes: &'a [usize],
    pub spatial: bool,
    pub magnification: f64,
    pub t_end: f64,
    /// The event threshold on the slip rate (m/s), for the slip-rate profile's scale.
    pub slip_rate_threshold: f64,
    /// The profile entities written ([`crate::sink::slip_front`]).
    pub profiles: Vec<String>,
}

/// A view's extra properties, written beside it.
struct Properties {
    path: String,
    batches: Vec<(&'static str, Vec<rerun::SerializedComponentBatch>)>,
}

/// Sends the default blueprint of `contents` to `rec`, active and default.
pub fn send(rec: &RecordingStream, contents: &Contents<'_>) -> rerun::RecordingStreamResult<()> {
    let mut properties = Vec::new();
    let root = root(contents, &mut properties);
    // The side panels start collapsed, so the views get the screen; one click opens them.
    let blueprint = Blueprint::new(root)
        .with_blueprint_panel(BlueprintPanel::new().with_state(PanelState::Collapsed))
        .with_selection_panel(SelectionPanel::new().with_state(PanelState::Collapsed))
        .with_time_panel(TimePanel::new().with_timeline(schema::SIM_TIME).with_state(PanelState::Collapsed));
    let activation = BlueprintActivation { make_active: true, make_default: true };
    // The SDK sends a blueprint through a stream; a memory stream hands its messages back.
    let (capture, collected) = collected::stream(RecordingStreamBuilder::new(schema::APP_ID))?;
    blueprint.send(&capture, activation)?;
    let mut messages: Vec<LogMsg> = collected
        .take(capture)
        .into_iter()
        .filter(|m| m.store_id().is_blueprint() && !matches!(m, LogMsg::BlueprintActivationCommand(_)))
        .collect();
    let Some(blueprint_id) = messages.first().map(|m| m.store_id().clone()) else {
        return Ok(());
    };
    let (extra, extra_collected) =
        collected::stream(RecordingStreamBuilder::from_store_id(&blueprint_id).send_properties(false))?;
    extra.set_time_sequence("blueprint", 0);
    for view in &properties {
        for (name, batches) in &view.batches {
            extra.log_serialized_batches(format!("{}/{name}", view.path), false, batches.iter().cloned())?;
        }
    }
    messages.extend(extra_collected.take(extra).into_iter().filter(|m| matches!(m, LogMsg::ArrowMsg(..))));
    rec.send_blueprint(messages, BlueprintActivationCommand { blueprint_id, make_active: true, make_default: true });
    Ok(())
}

/// The blueprint path of a view (`view/{id}`).
fn path_of(view: &ContainerLike) -> String {
    match view {
        ContainerLike::View(v) => v.blueprint_path().to_string().trim_start_matches('/').to_string(),
        _ => String::new(),
    }
}

/// A time series over the whole run, its legend in `corner` or hidden.
fn whole_run(
    view: TimeSeriesView,
    t_end: f64,
    legend: Option<Corner2D>,
    properties: &mut Vec<Properties>,
) -> ContainerLike {
    let view: ContainerLike = view.into();
    let range = TimeRange {
        start: TimeRangeBoundary::Absolute(TimeInt(0)),
        end: TimeRangeBoundary::Absolute(TimeInt((t_end * 1e9).round() as i64)),
    };
    let time_axis = TimeAxis::new().with_link(LinkAxis::Independent).with_view_range(range);
    properties.push(Properties {
        path: path_of(&view),
        batches: vec![("TimeAxis", time_axis.as_serialized_batches()), ("PlotLegend", legend_batches(legend))],
    });
    view
}

/// A plot's legend in `corner`, or hidden.
fn legend_batches(corner: Option<Corner2D>) -> Vec<rerun::SerializedComponentBatch> {
    match corner {
        Some(corner) => PlotLegend::new().with_corner(corner).with_visible(true),
        None => PlotLegend::new().with_visible(false),
    }
    .as_serialized_batches()
}

/// Instances of `recorded` that are named probes, as a visibility mask (every instance when
/// none is named).
fn probe_mask(recorded: &[usize], named: &dyn Fn(usize) -> bool) -> Vec<bool> {
    let mask: Vec<bool> = recorded.iter().map(|&k| named(k)).collect();
    if mask.iter().any(|&m| m) { mask } else { vec![true; recorded.len()] }
}

/// A time series of `entities`, each showing only the instances `mask` keeps.
fn probe_plot(name: &str, entities: &[(String, Option<Vec<bool>>)]) -> TimeSeriesView {
    let mut view = TimeSeriesView::new(name).with_contents(entities.iter().map(|(e, _)| format!("/{e}")));
    for (entity, mask) in entities {
        if let Some(mask) = mask {
            view = view.with_override(
                format!("/{entity}"),
                SeriesLines::update_fields().with_visible_series(mask.iter().copied()).visualizer(),
            );
        }
    }
    view
}

/// The colour key of a probe plot: the named probes (or the recorded ones' count) from purple
/// at the left to yellow at the right.
fn key(recorded: &[usize], name: &dyn Fn(usize) -> Option<String>) -> String {
    let names: Vec<String> = recorded.iter().filter_map(|&k| name(k)).collect();
    let which = match names.as_slice() {
        [] => format!("{} points", recorded.len()),
        [one] => one.clone(),
        [first, .., last] => format!("{first} to {last}"),
    };
    format!("{which} (purple: left, yellow: right)")
}

/// The bottom row: traction, structure and displacement at the probes, and the event log.
fn time_series(contents: &Contents<'_>, properties: &mut Vec<Properties>) -> ContainerLike {
    let layout = contents.layout;
    let segment_mask = probe_mask(contents.segments, &|k| layout.segments[k].name.is_some());
    let node_mask = probe_mask(contents.nodes, &|j| layout.surface_nodes[j].name.is_some());
    let segment_plot = |q: Quantity| vec![(schema::segment_entity(q), Some(segment_mask.clone()))];
    let mut displacement = Vec::new();
    if !contents.nodes.is_empty() {
        displacement.push((schema::node_entity(0).to_string(), Some(node_mask)));
    }
    if layout.kind == SceneKind::SpringBlock {
        displacement.push((schema::BLOCK_X.to_string(), None));
    }
    displacement.push((schema::BASE_UX.to_string(), None));
    let t_end = contents.t_end;
    // No legend over the data: the titles give the key, each probe coloured by its position
    // along the surface alike in every plot, and hovering a line names it.
    let segment_key = key(contents.segments, &|k| layout.segments[k].name.clone());
    let node_key = key(contents.nodes, &|j| layout.surface_nodes[j].name.clone());
    let traction = format!("{VIEW_TRACTION} at {segment_key}");
    let structure = format!("{VIEW_STRUCTURE} at {segment_key}");
    let displacement_name = format!("{VIEW_DISPLACEMENT} at {node_key}; grey: the base");
    Horizontal::new([
        whole_run(probe_plot(&traction, &segment_plot(Quantity::TractionT)), t_end, None, properties),
        whole_run(probe_plot(&structure, &segment_plot(Quantity::Structure)), t_end, None, properties),
        whole_run(probe_plot(&displacement_name, &displacement), t_end, None, properties),
        event_log(properties),
    ])
    .with_column_shares([3.0, 3.0, 3.0, 3.5])
    .into()
}

/// The event log: its level and text, without the entity path (always `/events`), so the text
/// has the width; each entry starts with its onset in seconds.
fn event_log(properties: &mut Vec<Properties>) -> ContainerLike {
    use rerun::external::re_sdk_types::blueprint::archetypes::TextLogColumns;
    use rerun::external::re_sdk_types::blueprint::components::TextLogColumn;
    use rerun::external::re_sdk_types::blueprint::datatypes::{self, TextLogColumnKind};
    let view: ContainerLike = TextLogView::new(VIEW_EVENTS).with_origin(format!("/{}", schema::EVENTS)).into();
    let column = |kind, visible: bool| TextLogColumn(datatypes::TextLogColumn { visible: visible.into(), kind });
    let columns = TextLogColumns::new().with_text_log_columns([
        column(TextLogColumnKind::LogLevel, true),
        column(TextLogColumnKind::Body, true),
        column(TextLogColumnKind::EntityPath, false),
    ]);
    properties
        .push(Properties { path: path_of(&view), batches: vec![("TextLogColumns", columns.as_serialized_batches())] });
    view
}

/// The top row: the block and, for a block of several segments, the profiles along x.
fn block_and_profiles(contents: &Contents<'_>, properties: &mut Vec<Properties>) -> ContainerLike {
    let block_name = if contents.magnification == 1.0 {
        VIEW_BLOCK.to_string()
    } else {
        format!("{VIEW_BLOCK} (displacements x{})", contents.magnification)
    };
    let block: ContainerLike = Spatial2DView::new(block_name).with_origin(format!("/{}", schema::SPATIAL)).into();
    if contents.profiles.is_empty() {
        return block;
    }
    let mut chart = |name: &str, entities: &[String]| -> ContainerLike {
        let view: ContainerLike =
            BarChartView::new(name).with_contents(entities.iter().map(|e| format!("/{e}"))).into();
        let legend = (entities.len() > 1).then_some(Corner2D::LeftTop);
        properties.push(Properties { path: path_of(&view), batches: vec![("PlotLegend", legend_batches(legend))] });
        view
    };
    let several = contents.layout.contacts.len() > 1;
    let mut per_contact: Vec<ContainerLike> = Vec::new();
    for (name, _, _) in contents.layout.contact_ranges() {
        let contact = several.then_some(name.as_str());
        let written = |quantities: &[&str]| -> Vec<String> {
            quantities
                .iter()
                .map(|q| schema::profile_entity(contact, q))
                .filter(|e| contents.profiles.contains(e))
                .collect()
        };
        // The block's contact runs along x; any other along its arc length.
        let along = |view: &str| match (contents.layout.kind, contact) {
            (SceneKind::Block, _) => view.to_string(),
            (_, Some(c)) => view.replacen("Along x (m)", &format!("Along {c} (m)"), 1),
            (_, None) => view.replacen("Along x (m)", "Along the contact (m)", 1),
        };
        let column: ContainerLike = Vertical::new([
            chart(&along(VIEW_STRENGTH), &written(&["static_strength", "kinetic_strength", "traction_t"])),
            chart(&along(&slip_rate_name(contents.slip_rate_threshold)), &written(&["slip_rate"])),
            chart(&along(VIEW_STRUCTURE_PROFILE), &written(&["structure"])),
        ])
        .with_row_shares(PROFILE_SHARES)
        .with_name(name)
        .into();
        per_contact.push(column);
    }
    let profiles: ContainerLike =
        if per_contact.len() == 1 { per_contact.remove(0) } else { Tabs::new(per_contact).into() };
    Horizontal::new([block, profiles]).with_column_shares([3.0, 2.0]).into()
}

/// The heights of the profiles (strength, slip rate, `1/R*`). A BarChartView in Rerun 0.36 has
/// no axis setting, and its plot labels the y axis only at ticks a power of ten apart that lie at
/// least 20 px apart. The strength profile of the paper case (0 to 480 Pa, ticks 100 Pa apart)
/// at a share of 2 of 4.4 in a top row of 3 of 9.8 had its ticks 17 px apart and showed only
/// `0`; at these shares in a top row of 3.6 they are 27 px apart, labelled 0 to 400 (official
/// viewer at 1920 × 1080, 2026-11-26).
const PROFILE_SHARES: [f32; 3] = [2.4, 1.4, 1.0];

/// The name of the slip-rate profile: its log scale and the floor it counts from
/// ([`crate::sink::slip_front::slip_rate_decades`]).
fn slip_rate_name(threshold: f64) -> String {
    let floor = crate::sink::slip_front::slip_rate_floor(threshold);
    format!("{VIEW_SLIP_RATE}, v0 = {floor:.0e} m/s: 2 is the event threshold, 4 is 100 times it")
}

/// The most stick/slip lanes that show whole beside the space-time map at open, on a
/// 1080-pixel screen: Rerun 0.36 draws a lane 22 px high, 1 px apart, under a 14-px label and a
/// 20-px time axis, and the middle row gets about 330 px.
pub const LANES_AT_OPEN: usize = 11;

/// The middle row: the space-time map, and the stick/slip lanes beside it while they fit
/// ([`LANES_AT_OPEN`]); more lanes go in a tab behind the map, which shows every segment.
fn map_and_lanes(contents: &Contents<'_>) -> ContainerLike {
    // The block's contact runs along x; a mesh's contacts along their arc lengths.
    let (lanes_name, map_name) = match contents.layout.kind {
        SceneKind::Block => (VIEW_STATE.to_string(), VIEW_SPACETIME.to_string()),
        _ => (
            VIEW_STATE.replace("from x = 0 at the top", "along each contact from its start, the first at the top"),
            VIEW_SPACETIME.replace("x down", "each contact's arc length down"),
        ),
    };
    let lanes: ContainerLike =
        StateTimelineView::new(lanes_name).with_contents([format!("/{}", schema::CONTACT_STATE)]).into();
    let map: ContainerLike = Spatial2DView::new(map_name).with_origin(format!("/{}", schema::SPACETIME)).into();
    if contents.segments.len() <= LANES_AT_OPEN {
        return Horizontal::new([map, lanes]).with_column_shares([3.0, 2.0]).into();
    }
    let active = path_of(&map);
    Tabs::new([map, lanes]).with_active_tab(active).into()
}

/// The whole layout; the time series' properties go into `properties`.
fn root(contents: &Contents<'_>, properties: &mut Vec<Properties>) -> ContainerLike {
    let series = time_series(contents, properties);
    if !contents.spatial {
        return series;
    }
    // The middle row keeps its 3.4 of 9.8 for its lanes (LANES_AT_OPEN); the top row takes 0.6
    // from the probe plots for the profiles' labels (PROFILE_SHARES).
    Vertical::new([block_and_profiles(contents, properties), map_and_lanes(contents), series])
        .with_row_shares([3.6, 3.4, 2.8])
        .into()
}
