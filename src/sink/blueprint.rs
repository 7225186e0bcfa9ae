//! The default blueprint sent with every recording: the spatial and space-time views on top,
//! time series of traction, `1/R*` and displacement at the probes below (the paper's Figures
//! 8 and 9), and the event log.

use rerun::blueprint::{
    Blueprint, ContainerLike, Horizontal, Spatial2DView, TextLogView, TimePanel, TimeSeriesView, Vertical,
};

use crate::frame::Quantity;
use crate::frame::{Layout, SceneKind};
use crate::record::schema;

/// Names of the views, for readers that check them.
pub const VIEW_BLOCK: &str = "Block";
pub const VIEW_SPACETIME: &str = "Space-time: slip rate";
pub const VIEW_TRACTION: &str = "Tangential traction f_t (Pa)";
pub const VIEW_STRUCTURE: &str = "Degree of structure 1/R*";
pub const VIEW_DISPLACEMENT: &str = "Displacement u_x (m)";
pub const VIEW_EVENTS: &str = "Slip events";

/// The default blueprint for a run over `layout` whose series cover `segments` and `nodes`.
pub fn default_blueprint(
    layout: &Layout,
    segments: &[usize],
    nodes: &[usize],
    spatial: bool,
    magnification: f64,
) -> Blueprint {
    // Plot the named probes when there are any, else every recorded segment and node.
    let probes = |recorded: &[usize], named: &dyn Fn(usize) -> bool| -> Vec<usize> {
        let chosen: Vec<usize> = recorded.iter().copied().filter(|&k| named(k)).collect();
        if chosen.is_empty() { recorded.to_vec() } else { chosen }
    };
    let plot_segments = probes(segments, &|k| layout.segments[k].name.is_some());
    let plot_nodes = probes(nodes, &|j| layout.surface_nodes[j].name.is_some());
    let segment_series = |q: Quantity| plot_segments.iter().map(|&k| schema::segment_entity(k, q)).collect::<Vec<_>>();

    let mut plots: Vec<ContainerLike> = vec![
        TimeSeriesView::new(VIEW_TRACTION).with_contents(segment_series(Quantity::TractionT)).into(),
        TimeSeriesView::new(VIEW_STRUCTURE).with_contents(segment_series(Quantity::Structure)).into(),
    ];
    let mut displacement: Vec<String> = plot_nodes.iter().map(|&j| schema::node_entity(j, 0)).collect();
    if layout.kind == SceneKind::SpringBlock {
        displacement.push(schema::BLOCK_X.into());
    }
    displacement.push(schema::BASE_UX.into());
    plots.push(TimeSeriesView::new(VIEW_DISPLACEMENT).with_contents(displacement).into());
    plots.push(TextLogView::new(VIEW_EVENTS).with_origin(format!("/{}", schema::EVENTS)).into());
    let plots = Horizontal::new(plots);

    let root: ContainerLike = if spatial {
        let block_name = if magnification == 1.0 {
            VIEW_BLOCK.to_string()
        } else {
            format!("{VIEW_BLOCK} (displacements x{magnification})")
        };
        Vertical::new([
            Horizontal::new([
                Spatial2DView::new(block_name).with_origin(format!("/{}", schema::SPATIAL)).into(),
                Spatial2DView::new(VIEW_SPACETIME).with_origin(format!("/{}", schema::SPACETIME)).into(),
            ])
            .with_column_shares([3.0, 2.0])
            .into(),
            plots.into(),
        ])
        .into()
    } else {
        plots.into()
    };
    Blueprint::new(root).with_time_panel(TimePanel::new().with_timeline(schema::SIM_TIME))
}
