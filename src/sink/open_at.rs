//! A blueprint file that opens a recording at a chosen simulated time.
//!
//! Rerun 0.36 has no blueprint setting for the time cursor, and its `#when=` URL fragment
//! moves it only in a dataset served by a Rerun server, not in a file. What a blueprint can set
//! is the time panel's play state, loop mode, speed and time selection; a viewer playing with
//! the loop on the selection sends the cursor back to the selection's start whenever it passes
//! the end (`re_viewer_context`'s time control, 0.36.2). A selection of zero length at `T`,
//! played at [`PINNING_SPEED`] (a simulated day per wall second), therefore holds the cursor
//! at `T` from the first frame. The file adds these rows to the recording's own blueprint
//! store, which the recording makes active and default, so the recording opens on its usual
//! layout whichever of the two files the viewer reads first.

use std::path::Path;

use rerun::RecordingStreamBuilder;
use rerun::blueprint::components::{LoopMode, PlayState};
use rerun::external::re_log_types::StoreId;
use rerun::external::re_sdk_types::blueprint::archetypes::TimePanelBlueprint;
use rerun::external::re_sdk_types::blueprint::components::PlaybackSpeed;
use rerun::external::re_sdk_types::datatypes::{AbsoluteTimeRange, TimeInt};

use crate::record::schema;

/// The playback speed that pins the cursor: one step of the viewer's clock (at most 0.1 s of
/// wall time) moves it far past any selection's end.
pub const PINNING_SPEED: f64 = 86_400.0;

/// Writes to `path` a blueprint for the blueprint store `blueprint` (a recording's own,
/// [`crate::inspect::rrd::blueprint_store`]) that holds the time cursor at `time` seconds of
/// `sim_time`.
pub fn write(path: &Path, blueprint: &StoreId, time: f64) -> Result<(), String> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
    let rec =
        RecordingStreamBuilder::from_store_id(blueprint).send_properties(false).save(path).map_err(|e| fail(&e))?;
    // After the recording's own blueprint rows (blueprint time 0), so these win.
    rec.set_time_sequence("blueprint", 1);
    let at = TimeInt((time * 1e9).round() as i64);
    let panel = TimePanelBlueprint::new()
        .with_timeline(schema::SIM_TIME)
        .with_play_state(PlayState::Playing)
        .with_loop_mode(LoopMode::Selection)
        .with_playback_speed(PlaybackSpeed(PINNING_SPEED.into()))
        .with_time_selection(AbsoluteTimeRange { min: at, max: at });
    rec.log("time_panel", &panel).map_err(|e| fail(&e))?;
    rec.flush_blocking().map_err(|e| fail(&e))?;
    Ok(())
}
