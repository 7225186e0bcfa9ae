//! `slipfront view RECORDING --at SECONDS`: the blueprint file that opens a recording at a
//! chosen time extends the recording's own blueprint store with a time panel that holds the
//! cursor there, and bad input is refused with exit 2.

mod common;

use std::path::PathBuf;

use common::{binary, case_path};
use rerun::external::re_log_encoding::DecoderApp;
use rerun::log::{Chunk, LogMsg};

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slipfront-view-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every message of a Rerun file.
fn messages(path: &std::path::Path) -> Vec<LogMsg> {
    DecoderApp::decode_eager(std::io::BufReader::new(std::fs::File::open(path).unwrap()))
        .unwrap()
        .map(Result::unwrap)
        .collect()
}

#[test]
fn the_blueprint_file_holds_the_cursor_at_the_time_asked_in_the_recordings_layout() {
    let out = scratch("at");
    let status = binary()
        .args(["run", &case_path("paper_triangular.toml"), "--quiet", "--set", "time.t_end=450", "--out-dir"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let rrd = out.join("paper_triangular.rrd");
    let output = binary().arg("view").arg(&rrd).args(["--at", "425.3", "--no-open"]).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let rbl = out.join("paper_triangular.at-425.3s.rbl");
    assert!(stdout.contains(&format!("rerun {} {}", rrd.display(), rbl.display())), "{stdout}");

    // The recording's blueprint store, as the recording itself names it.
    let recorded = messages(&rrd).into_iter().find(|m| m.store_id().is_blueprint()).unwrap().store_id().clone();
    let written = messages(&rbl);
    assert!(written.iter().all(|m| m.store_id() == &recorded), "every message extends the recording's blueprint");
    // The time panel: on sim_time, playing a loop of zero length at 425.3 s, fast.
    let panel = written
        .iter()
        .filter_map(|m| match m {
            LogMsg::ArrowMsg(_, arrow) => Some(Chunk::from_arrow_msg(arrow).unwrap()),
            _ => None,
        })
        .find(|c| c.entity_path().to_string() == "/time_panel")
        .expect("a time panel");
    let component = |name: &str| {
        use rerun::external::re_sdk_types::blueprint::archetypes::TimePanelBlueprint as Panel;
        let descriptor = match name {
            "timeline" => Panel::descriptor_timeline(),
            "time_selection" => Panel::descriptor_time_selection(),
            "playback_speed" => Panel::descriptor_playback_speed(),
            "play_state" => Panel::descriptor_play_state(),
            _ => Panel::descriptor_loop_mode(),
        };
        panel.components().get_array(descriptor.component).unwrap_or_else(|| panic!("no {name}")).clone()
    };
    let debug = |name: &str| format!("{:?}", component(name));
    assert!(debug("timeline").contains("sim_time"), "{}", debug("timeline"));
    assert!(debug("time_selection").contains("425300000000"), "{}", debug("time_selection"));
    assert!(debug("playback_speed").contains("86400"), "{}", debug("playback_speed"));
    // PlayState::Playing is 2, LoopMode::Selection is 2 (rerun.blueprint.components).
    let first_u8 = |name: &str| {
        use rerun::external::arrow::array::{Array, ListArray, UInt8Array};
        let list = component(name);
        let list =
            list.as_any().downcast_ref::<ListArray>().unwrap_or_else(|| panic!("{name}: {:?}", list.data_type()));
        list.values().as_any().downcast_ref::<UInt8Array>().unwrap().value(0)
    };
    assert_eq!(first_u8("play_state"), 2, "playing");
    assert_eq!(first_u8("loop_mode"), 2, "looping on the selection");
}

#[test]
fn bad_input_is_refused_with_exit_2() {
    let out = scratch("bad");
    let csv = out.join("x.csv");
    std::fs::write(&csv, "not a recording").unwrap();
    for (args, says) in [
        (vec!["view".to_string(), csv.display().to_string(), "--at".into(), "-1".into()], "--at = -1 must be"),
        (vec!["view".into(), out.join("none.rrd").display().to_string(), "--at".into(), "1".into()], "no such file"),
        (vec!["view".into(), csv.display().to_string(), "--at".into(), "1".into()], "is not a Rerun recording"),
        (vec!["view".into(), csv.display().to_string(), "--at".into(), "soon".into()], "invalid value 'soon'"),
    ] {
        let output = binary().args(&args).arg("--no-open").output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
    }
}
