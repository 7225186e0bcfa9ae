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
