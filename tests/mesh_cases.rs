//! Bodies from Gmsh meshes, each against something independent: the paper's block as the
//! structured `kind = "block"` builds it, the same block rotated, and closed forms of a shear
//! column of one and of two materials. The meshes are committed (cases/meshes/, tests/meshes/),
//! written by Gmsh 4.15.2 from the `.geo` files beside them, so no test needs Gmsh.

mod common;

use slipfront::case::{self, Case};
use slipfront::frame::Needs;
use slipfront::run::{LoopOptions, Outcome, run};
use slipfront::scene;
use slipfront::sink::catalog::{events_csv, ruptures_csv};

/// A file under the repository.
fn repository(path: &str) -> String {
    format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))
}

/// `cases/paper_mesh.toml` with its mesh replaced by `mesh` and `overrides`.
fn paper_mesh(mesh: &str, overrides: &[&str]) -> Case {
    let file = format!("scene.file=\"{}\"", repository(mesh));
    let mut all = vec![file.as_str()];
    all.extend_from_slice(overrides);
    common::load("paper_mesh", &all)
}

/// A case of `text` whose files are found from the repository's `tests/meshes/`.
fn from_text(text: &str, overrides: &[&str]) -> Case {
    let owned: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let dir = repository("tests/meshes");
    case::from_str_at(text, &owned, std::path::Path::new(&dir)).unwrap_or_else(|e| panic!("{e}"))
}

/// The event and rupture catalogs of a complete run of `case`, as the CSV files hold them.
fn catalogs(case: &Case) -> (String, String) {
    let mut scene = scene::build(case).unwrap();
    match run(scene.as_mut(), &case.time, &mut Vec::new(), LoopOptions::for_case(case)) {
        Outcome::Completed { catalog, .. } => (events_csv(&catalog.events), ruptures_csv(&catalog.ruptures)),
        other => panic!("the run did not complete: {other:?}"),
    }
}

/// The reader renumbers any file to one canonical order and the element matrices are computed
/// from each cell's corners relative to its first (canonical) corner, so the paper's block as
/// Gmsh writes it, in every form, is the block that `kind = "block"` builds, sum for sum: the
/// catalogs are identical byte for byte, with the default integrator and with Wilson's. The
/// file written with `Mesh.SaveAll` has no surface group: its material names none.
#[test]
fn the_paper_block_from_gmsh_in_every_form_gives_the_blocks_catalogs_byte_for_byte() {
    let files = [
        "cases/meshes/paper_block.msh",
        "cases/meshes/paper_block_binary.msh",
        "cases/meshes/paper_block_v2.msh",
        "cases/meshes/paper_block_shuffled.msh",
        "cases/meshes/paper_block_saveall.msh",
    ];
    let paper = std::fs::read_to_string(repository("cases/paper_mesh.toml")).unwrap();
    let any_cell = paper.replace("group = \"body\"", "# every cell");
    assert_ne!(any_cell, paper);
    for integrator in ["auto", "wilson"] {
        let set = format!("time.integrator=\"{integrator}\"");
        let block = catalogs(&common::load("paper_triangular", &[&set]));
        assert!(block.0.lines().count() > 20, "the block slips: {}", block.0);
        for file in files {
            let text = if file.contains("saveall") { &any_cell } else { &paper };
            let overrides = [format!("scene.file=\"{}\"", repository(file)), set.clone()];
            let case = case::from_str_at(text, &overrides, std::path::Path::new(&repository("cases"))).unwrap();
            let mesh = catalogs(&case);
            assert!(mesh == block, "{file} with {integrator}: the catalogs differ from the block's");
        }
    }
}

/// The paper's block and its loading rotated together by 30° (tests/meshes/block_rotated.geo;
/// the triangle of normal traction given along the contact's arc length, the base moving along
/// its tangent). The rotation changes the rounding of every element matrix, so the runs are not
/// identical to the bit. With Wilson's fixed steps that rounding is all that differs: the first
/// four onsets agree within 1e-9 relative (measured 1.3e-10). An adaptive method's steps follow its error estimate, which
/// rounding moves, so its onsets agree to its own accuracy instead: the default within 5e-6
/// relative (measured 5.4e-9; its documented accuracy is 2e-3 s at 420 s), and at a tolerance
/// of 1e-10 within 2e-8 (measured 4.9e-9). With every method the segments' tractions in the
/// local frame agree every 50 s up to 400 s, before the first slips, within a billionth of the
/// weakest static strength (measured 2.4e-9 Pa with Wilson, 1.5e-8 Pa with Tsit5, of 140 Pa).
#[test]
fn the_block_rotated_gives_the_same_onsets_and_local_tractions() {
    let along_arc = "scene.contacts.0.normal_traction={kind=\"linear\", along=\"arc\", at=[0, 10], value=[350, 1200]}";
    let runs: [(&[&str], f64); 3] = [
        (&["time.integrator=\"wilson\""], 1e-9),
        (&["time.integrator=\"auto\""], 5e-6),
        (&["time.integrator=\"tsit5\"", "time.tolerance=1e-10"], 2e-8),
    ];
    for (sets, onset_bound) in runs {
        let mut block_sets = sets.to_vec();
        block_sets.push("time.t_end=440");
        let mut rotated_sets = block_sets.clone();
        rotated_sets.push(along_arc);
        let block = common::load("paper_triangular", &block_sets);
        let rotated = paper_mesh("tests/meshes/block_rotated.msh", &rotated_sets);
        let (a, b) = (common::onsets(&block), common::onsets(&rotated));
        assert!(a.len() >= 4, "{sets:?}: the block has {} events by 440 s", a.len());
        for (k, (x, y)) in a.iter().zip(&b).take(4).enumerate() {
            assert_eq!(x.0, y.0, "{sets:?}: event {k} on another segment");
            let relative = (x.1 - y.1).abs() / x.1;
            println!("{sets:?}: onset {k} at {} s, rotated {} s, relative difference {relative:.1e}", x.1, y.1);
            assert!(relative < onset_bound, "{sets:?}: onset {k}: {} against {} s", y.1, x.1);
        }
        let (a, b) = (common::tractions(&block, 50.0), tractions(&rotated, 50.0));
        let strength = 0.4 * 350.0;
        let worst = common::max_difference(&a[..8], &b[..8]);
        println!("{sets:?}: largest traction difference up to 400 s: {worst:.1e} Pa");
        assert!(worst < 1e-9 * strength, "{sets:?}: tractions differ by {worst} Pa before the first slips");
    }
}

/// Mean tangential traction of each segment every `every` seconds (any scene).
fn tractions(case: &Case, every: f64) -> Vec<Vec<f64>> {
    let mut scene = scene::build(case).unwrap();
    let adaptive = case.time.adaptive_tolerance().is_some();
    let samples = (case.time.t_end / every).round() as usize;
    let mut out = Vec::new();
    for k in 1..=samples {
        let target = k as f64 * every;
        while scene.time() < target - 1e-9 {
            let left = target - scene.time();
            scene.advance(if adaptive { left } else { case.time.dt.min(left) }).unwrap();
        }
        out.push(scene.frame(Needs::default(), 0.0).segments.iter().map(|s| s.traction_t).collect());
    }
    out
}

/// The friction force per unit base displacement once a stuck block's transients have decayed
/// (t in [40, 50] s, every second), for a case driven at 1 mm/s after a 10 s ramp; the largest
/// relative spread of that stiffness over the samples is returned too.
fn stuck_stiffness(case: &Case) -> (f64, f64) {
    let mut scene = scene::build(case).unwrap();
    let dt = case.time.dt;
    let mut samples = Vec::new();
    let steps = (50.0 / dt).round() as usize;
    for k in 1..=steps {
        scene.advance(k as f64 * dt - scene.time()).unwrap();
        if scene.time() >= 40.0 - 1e-9 && k % (1.0 / dt).round() as usize == 0 {
            let frame = scene.frame(Needs::default(), dt);
            assert!(frame.segments.iter().all(|s| s.slip_rate < 1e-6), "the contact slipped at {} s", frame.time);
            samples.push(frame.friction_force / frame.base_displacement);
        }
    }
    let mean = samples.iter().sum::<f64>() / samples.len() as f64;
    let spread = samples.iter().map(|s| (s - mean).abs() / mean).fold(0.0, f64::max);
    (mean, spread)
}

/// A stuck contact (μ 200 and 400) under a uniform 1000 Pa, Wilson at 0.01 s for 50 s.
const STUCK: [&str; 6] = [
    "friction.mu_s=400",
    "friction.mu_k=200",
    "time.integrator=\"wilson\"",
    "time.dt=0.01",
    "time.t_end=50",
    "record.spatial=false",
];

/// A case text for a mesh of `tests/meshes/` with the paper's friction and time, a fixed top,
/// and a bottom contact under 1000 Pa; `rest` adds materials and boundaries.
fn stuck_case_text(mesh: &str, rest: &str) -> String {
    let paper = std::fs::read_to_string(repository("cases/paper_mesh.toml")).unwrap();
    let head = &paper[..paper.find("[scene]").unwrap()];
    format!(
        "{head}[scene]\nkind = \"mesh\"\nfile = \"{mesh}\"\n\n{rest}\n[[scene.boundaries]]\ngroup = \"top\"\nfixed = \"xy\"\n\n\
         [[scene.contacts]]\ngroup = \"bottom\"\nbase_velocity = 1.0e-3\nbase_ramp_time = 10.0\n\
         normal_traction = {{ kind = \"uniform\", value = 1000.0 }}\n"
    )
}

const BODY: &str =
    "[[scene.materials]]\ngroup = \"body\"\nyoungs_modulus = 1.0e3\npoisson_ratio = 0.0\ndensity = 1000.0\n";
const ROLLER_SIDES: &str =
    "[[scene.boundaries]]\ngroup = \"left\"\nfixed = \"y\"\n\n[[scene.boundaries]]\ngroup = \"right\"\nfixed = \"y\"\n";

/// The stuck limit's closed form (docs/model.md) is the block as a shear column in series with
/// the contact spring: `F / u_base = W / (H/G + 1/α_t)`. It is the exact continuum solution when
/// the sides may not move vertically (simple shear needs the vertical shear traction there):
/// with the sides on rollers, every triangle mesh reproduces it, whatever its size (linear
/// elements hold a linear field exactly), up to what is left of the ramp's ringing.
///
/// With free sides, as in the paper, the ends relieve the shear: the limit lies below the
/// closed form, which is then the wrong reference, so the triangles' convergence is measured
/// against the same block in bilinear quadrilaterals, an element of another kind: the limits
/// that Richardson's extrapolation gives from each sequence (h = 0.5, 0.25, 0.125 m against
/// 40 × 4, 80 × 8, 160 × 16) agree, and each sequence converges at an observed order of at least 1.
#[test]
fn triangles_converge_on_the_stuck_block_and_hold_the_closed_form_where_it_is_exact() {
    let (w, h, g, alpha) = (10.0, 1.0, 500.0, 1.0e6);
    let closed_form = w / (h / g + 1.0 / alpha);
    let sizes = ["0.5", "0.25", "0.125"];
    for size in sizes {
        let text = stuck_case_text(&format!("block_triangles_h{size}.msh"), &format!("{BODY}\n{ROLLER_SIDES}"));
        let (stiffness, spread) = stuck_stiffness(&from_text(&text, &STUCK));
        let error = (stiffness - closed_form).abs() / closed_form;
        println!("triangles h = {size} m, sides on rollers: {error:.2e} from the closed form (spread {spread:.1e})");
        assert!(error < 5e-4, "h = {size}: {stiffness} N/m² against {closed_form}");
    }
    let triangles: Vec<f64> = sizes
        .iter()
        .map(|size| {
            stuck_stiffness(&from_text(&stuck_case_text(&format!("block_triangles_h{size}.msh"), BODY), &STUCK)).0
        })
        .collect();
    let quads: Vec<f64> = [(40, 4), (80, 8), (160, 16)]
        .iter()
        .map(|(nx, ny)| {
            let (nx, ny) = (format!("scene.nx={nx}"), format!("scene.ny={ny}"));
            let mut sets: Vec<&str> = STUCK.to_vec();
            sets.extend([nx.as_str(), ny.as_str(), "scene.normal_traction={kind=\"uniform\", value=1000}"]);
            stuck_stiffness(&common::load("paper_triangular", &sets)).0
        })
        .collect();
    let (t_limit, t_order) = richardson(&triangles);
    let (q_limit, q_order) = richardson(&quads);
    println!("free sides: triangles {triangles:?} N/m², limit {t_limit:.4}, observed order {t_order:.2}");
    println!("free sides: quadrilaterals {quads:?} N/m², limit {q_limit:.4}, observed order {q_order:.2}");
    println!(
        "closed form {closed_form:.4}: the free-sided limit lies {:.2} % below it",
        100.0 * (closed_form - q_limit) / closed_form
    );
    assert!(t_order >= 1.0 && q_order >= 1.0, "observed orders {t_order} and {q_order}");
    assert!((t_limit - q_limit).abs() / q_limit < 2e-3, "limits {t_limit} (triangles) and {q_limit} (quadrilaterals)");
    for e in [&triangles, &quads] {
        assert!(e.windows(2).all(|p| p[1] < p[0]), "each refinement softens the mesh: {e:?}");
    }
}

/// The limit and observed order of three values on meshes halved each time:
/// `p = log2((f₁ - f₂)/(f₂ - f₃))`, `f* = f₃ - (f₂ - f₃)/(2^p - 1)`.
fn richardson(f: &[f64]) -> (f64, f64) {
    let order = ((f[0] - f[1]) / (f[1] - f[2])).log2();
    (f[2] - (f[1] - f[2]) / (2f64.powf(order) - 1.0), order)
}

/// Two materials in series (tests/meshes/two_layers.geo: E = 1 kPa below y = 0.4 m, 5 kPa
/// above, triangles of 0.25 m), the sides on rollers and the contact stuck: the shear column
/// of two layers in series with the contact spring, `F / u_base = W / (h₁/G₁ + h₂/G₂ + 1/α_t)`.
#[test]
fn two_materials_in_series_carry_the_closed_form_force() {
    let materials = "[[scene.materials]]\ngroup = \"soft\"\nyoungs_modulus = 1.0e3\npoisson_ratio = 0.0\ndensity = 1000.0\n\n\
                     [[scene.materials]]\ngroup = \"stiff\"\nyoungs_modulus = 5.0e3\npoisson_ratio = 0.0\ndensity = 1000.0\n\n\
                     [[scene.boundaries]]\ngroup = \"sides\"\nfixed = \"y\"\n";
    let (stiffness, _) = stuck_stiffness(&from_text(&stuck_case_text("two_layers.msh", materials), &STUCK));
    let (g1, g2) = (500.0, 2500.0);
    let closed_form = 10.0 / (0.4 / g1 + 0.6 / g2 + 1.0 / 1.0e6);
    let error = (stiffness - closed_form).abs() / closed_form;
    println!("two layers: {stiffness} N/m² against {closed_form}: {error:.1e}");
    assert!(error < 1e-4, "{stiffness} against {closed_form}");
    // Either material alone is far off: the test tells the layers apart.
    for g in [g1, g2] {
        assert!((10.0 / (1.0 / g + 1.0 / 1.0e6) - stiffness).abs() / stiffness > 0.3);
    }
}

/// The double-shear sample (cases/double_shear.toml) with the right contact given the left's
/// friction is its own mirror image about x = 1 m: the mesh, the piston and the clamps are
/// symmetric, and walked counter-clockwise the left contact runs down and the right one up, so
/// left segment `i` (from the top) mirrors segment `47 - i`, with the traction's sign turned.
/// Each segment's first slip starts when its mirror's does, and no rupture spans the two
/// contacts, though both slip at once. As shipped, the weaker left contact slips first.
#[test]
fn the_double_shear_sample_with_equal_contacts_slips_as_its_mirror_image() {
    let equal = ["time.t_end=260", "scene.contacts.1.friction.mu_s=0.4", "scene.contacts.1.friction.mu_k=0.2"];
    let catalog = |overrides: &[&str]| {
        let case = common::load("double_shear", overrides);
        let mut scene = scene::build(&case).unwrap();
        match run(scene.as_mut(), &case.time, &mut Vec::new(), LoopOptions::for_case(&case)) {
            Outcome::Completed { catalog, .. } => catalog,
            other => panic!("the run did not complete: {other:?}"),
        }
    };
    let symmetric = catalog(&equal);
    let first = |segment: usize| symmetric.events.iter().find(|e| e.segment == segment);
    let mut compared = 0;
    let mut worst: f64 = 0.0;
    for i in 0..24 {
        let (Some(left), Some(right)) = (first(i), first(47 - i)) else {
            assert!(first(i).is_none() && first(47 - i).is_none(), "segment {i} slips and its mirror does not");
            continue;
        };
        let onset = (left.onset - right.onset).abs() / left.onset;
        let traction = (left.traction_before + right.traction_before).abs() / left.traction_before.abs();
        worst = worst.max(onset).max(traction);
        assert!(onset < 1e-9 && traction < 1e-9, "segment {i}: {left:?} against its mirror {right:?}");
        compared += 1;
    }
    println!("{compared} mirror pairs, worst relative difference {worst:.1e} (onset, traction)");
    assert!(compared >= 12, "only {compared} segments slipped by 260 s");
    let both = |r: &slipfront::catalog::events::Rupture| (r.first_segment < 24) != (r.last_segment < 24);
    assert!(!symmetric.ruptures.iter().any(both), "a rupture spans both contacts: {:?}", symmetric.ruptures);
    let onsets = |c: &slipfront::catalog::events::Catalog, range: std::ops::Range<usize>| {
        c.events.iter().filter(|e| range.contains(&e.segment)).map(|e| e.onset).fold(f64::INFINITY, f64::min)
    };
    let (left, right) = (onsets(&symmetric, 0..24), onsets(&symmetric, 24..48));
    assert!((left - right).abs() < 1e-9 * left, "first slips at {left} s and {right} s");
    let shipped = catalog(&["time.t_end=260"]);
    assert!(onsets(&shipped, 0..24) < onsets(&shipped, 24..48), "the weaker left contact slips first");
}

/// A case naming the groups of tests/meshes/groups.msh (a rectangle of two surfaces in one
/// group "body", with curve groups that are not one open chain) with `set` applied.
fn groups_case(set: &[&str]) -> Result<Case, String> {
    groups_case_text(&stuck_case_text("groups.msh", BODY), set)
}

fn groups_case_text(text: &str, set: &[&str]) -> Result<Case, String> {
    let owned: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    case::from_str_at(text, &owned, std::path::Path::new(&repository("tests/meshes"))).map_err(|e| e.to_string())
}

/// Every mistake in naming the mesh's groups is refused before anything runs, naming the key,
/// the group and what the mesh has or what is allowed.
#[test]
fn groups_the_mesh_lacks_or_that_cannot_serve_are_refused_naming_them() {
    groups_case(&[]).unwrap();
    let refused = [
        (
            "scene.materials.0.group=\"soil\"",
            "scene.materials[0].group = \"soil\" names no group of the mesh; it has \"corner\" (point), \"bottom\" \
             (curve), \"top\" (curve), \"outline\" (curve), \"bottom_and_top\" (curve), \"inner\" (curve), \"right\" \
             (curve), \"body\" (surface)",
        ),
        (
            "scene.materials.0.group=\"bottom\"",
            "scene.materials[0].group = \"bottom\" is a curve group; a surface group is needed here",
        ),
        (
            "scene.contacts.0.group=\"outline\"",
            "scene.contacts[0].group = \"outline\" is not one open chain of boundary edges: physical group \"outline\" \
             is a closed loop of 20 lines (through node 1)",
        ),
        (
            "scene.contacts.0.group=\"bottom_and_top\"",
            "physical group \"bottom_and_top\" has 2 disjoint pieces (from node 1 to node 3, from node 4 to node 6)",
        ),
        ("scene.contacts.0.group=\"inner\"", "it is inside the body, not on its boundary"),
        ("scene.contacts.0.group=\"corner\"", "scene.contacts[0].group = \"corner\" is a point group"),
    ];
    for (set, says) in refused {
        let error = groups_case(&[set]).err().unwrap_or_else(|| panic!("{set} was accepted"));
        assert!(error.contains(says), "{set}: {error}");
    }
    // The right side moved: its bottom node is the contact's last. A fixed side is accepted
    // (the contact sees the node still).
    let fixed_right = stuck_case_text("groups.msh", BODY).replace("group = \"top\"", "group = \"right\"");
    groups_case_text(&fixed_right, &[]).unwrap();
    let moved_right = fixed_right.replace("fixed = \"xy\"", "velocity = [0.0, 1.0e-3]");
    let error = groups_case_text(&moved_right, &[]).unwrap_err();
    let says = "scene.boundaries = [...] the node at (4, 0) is on contact \"bottom\" and on a boundary that moves it; \
                a contact's nodes may be fixed but not moved";
    assert!(error.contains(says), "{error}");
}
