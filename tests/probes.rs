//! Probes given by position name the node, or the segment whose centre, lies nearest (worked
//! out by hand from the geometry), and a run whose named probes crowd into part of their
//! contact says so on stderr at its start.

mod common;

use common::{binary, case_path, load};
use slipfront::case::Case;
use slipfront::frame::Layout;
use slipfront::scene;

/// Names by index: `(index, name)` of every named one.
type Named = Vec<(usize, String)>;

/// The names the layout of `case`'s scene gives its segments and its surface nodes.
fn named(case: &Case) -> (Named, Named) {
    let scene = scene::build(case).unwrap();
    let layout: &Layout = scene.layout();
    let names = |names: Vec<Option<&String>>| -> Named {
        names.into_iter().enumerate().filter_map(|(i, n)| n.map(|n| (i, n.clone()))).collect()
    };
    (
        names(layout.segments.iter().map(|s| s.name.as_ref()).collect()),
        names(layout.surface_nodes.iter().map(|n| n.name.as_ref()).collect()),
    )
}

#[test]
fn probes_by_position_name_the_nearest_node_and_segment_of_the_block() {
    // A 20 m block of 40 elements: nodes at x = 0.5 j, segment centres at 0.25 + 0.5 k (m).
    let case = load(
        "paper_triangular",
        &[
            "scene.width=20",
            "scene.nx=40",
            // 3.3 is 0.2 from node 7 (3.5), 0.3 from node 6; -5 lies left of node 0; [12.26, 7]
            // is nearest node 25 (12.5, 0.24 away in x, every node at y = 0); index 40 is the
            // last node, numbered as given.
            "probes.nodes=[{name=\"a\", x=3.3}, {name=\"b\", x=-5}, {name=\"c\", at=[12.26, 7]}, {name=\"d\", index=40}]",
            // 3.3 is 0.05 from segment 6 (3.25); 100 lies right of the last, 39 (19.75);
            // [0.74, -1] is nearest segment 1 (0.75); 0.5 is as near segment 0 (0.25) as 1
            // (0.75): the first of equals.
            "probes.segments=[{name=\"s\", x=3.3}, {name=\"t\", x=100}, {name=\"u\", at=[0.74, -1]}, {name=\"v\", x=0.5}]",
        ],
    );
    let (segments, nodes) = named(&case);
    let expect = |list: &[(usize, &str)]| list.iter().map(|&(i, n)| (i, n.to_string())).collect::<Vec<_>>();
    assert_eq!(nodes, expect(&[(0, "b"), (7, "a"), (25, "c"), (40, "d")]));
    assert_eq!(segments, expect(&[(0, "v"), (1, "u"), (6, "s"), (39, "t")]));
}

#[test]
fn probes_by_point_take_the_nearest_contact_of_several() {
    // The double-shear sample: its left contact on x = 0 runs down from y = 6 m (the body on
    // its left), its right one on x = 2 m runs up, each in 24 segments of 0.25 m. The shipped
    // probes name the end segments and those centred at y = 3.125 m of each (left: 11, 6 -
    // 0.125 - 0.25 k; right: 24 + 12, 0.125 + 0.25 k). [1.2, 2.9] lies 0.8 m from the right
    // contact and 1.2 m from the left, nearest the right one's centre at y = 2.875 (24 + 11).
    let case = load("double_shear", &["probes.nodes=[]"]);
    let (segments, _) = named(&case);
    let expect = |list: &[(usize, &str)]| list.iter().map(|&(i, n)| (i, n.to_string())).collect::<Vec<_>>();
    assert_eq!(
        segments,
        expect(&[(0, "L top"), (11, "L mid"), (23, "L low"), (24, "R low"), (36, "R mid"), (47, "R top")])
    );
    let case = load("double_shear", &["probes.nodes=[]", "probes.segments=[{name=\"p\", at=[1.2, 2.9]}]"]);
    assert_eq!(named(&case).0, expect(&[(35, "p")]));
}

/// `slipfront run cases/paper_triangular.toml` for 1 s with `sets`: (exit code, stderr).
fn run_paper(sets: &[&str], extra: &[&str]) -> (Option<i32>, String) {
    let out = std::env::temp_dir().join(format!("slipfront-probes-{}", std::process::id()));
    let mut command = binary();
    command.args(["run", &case_path("paper_triangular.toml"), "--no-rrd", "--out-dir"]).arg(&out);
    for set in sets.iter().chain(&["time.t_end=1"]) {
        command.args(["--set", set]);
    }
    let output = command.args(extra).output().unwrap();
    (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned())
}

#[test]
fn probes_crowded_into_part_of_the_contact_are_warned_of_at_the_start() {
    // The paper case's probes are at 0.5 to 9.5 m (segments) and 0 to 10 m (nodes): on a block
    // twice as wide the segments sit in less than half of it (the nodes in exactly half).
    let wider = ["scene.width=20", "scene.height=2", "scene.nx=40", "scene.ny=4"];
    let (code, stderr) = run_paper(&wider, &[]);
    assert_eq!(code, Some(0), "{stderr}");
    let warning = "slipfront: warning: the 6 named probes.segments lie within 0.25 to 9.25 m of the contact's 20 m \
                   (arc length), though the probe plots colour them from its start to its end as if they spread \
                   along it: place them along the whole contact in the case's [probes], by position (x = ... or at \
                   = [x, y], in m) to hold them there when the mesh changes\n";
    assert!(stderr.starts_with(warning), "{stderr}");
    assert_eq!(stderr.matches("warning").count(), 1, "the nodes spread over half the contact: {stderr}");
    // The same mesh on the paper's 10 m keeps its probes spread; --quiet says nothing.
    let (code, stderr) = run_paper(&["scene.nx=40", "scene.ny=4"], &[]);
    assert!(code == Some(0) && !stderr.contains("warning"), "{stderr}");
    let (code, stderr) = run_paper(&wider, &["--quiet"]);
    assert!(code == Some(0) && stderr.is_empty(), "{stderr}");
}
