//! The unit of a case key, as docs/cases.md gives it, for labels that name a key (a study's
//! swept parameters on a figure's axis).

/// The unit of `key`, a dotted path as in `--set` (`scene.normal_traction.left`,
/// `scene.phases.1.velocity`): `"-"` for a pure number, `None` for a key whose unit depends on
/// the case (`time.tolerance`), is not a number, or is not known here.
pub fn unit_of(key: &str) -> Option<&'static str> {
    let parts: Vec<&str> = key.split('.').filter(|p| p.parse::<usize>().is_err()).collect();
    let (&last, path) = parts.split_last()?;
    if path.contains(&"normal_traction") || last == "normal_traction" {
        return Some(if last == "x" { "m" } else { "Pa" });
    }
    if path.contains(&"gap") || last == "gap" {
        return Some("m");
    }
    Some(match last {
        "mu_s" | "mu_k" | "m" | "n" | "structure0" | "theta" | "energy_tolerance" | "accuracy" | "nx" | "ny"
        | "poisson_ratio" => "-",
        "alpha_n" | "alpha_t" | "stiffness" => "Pa/m",
        "r" | "kappa" => "1/m",
        "xi" => "1/s",
        "f0" | "youngs_modulus" | "traction" | "pressure" => "Pa",
        "t_end" | "dt" | "dt_max" | "base_ramp_time" | "ramp_time" | "duration" | "merge_within" => "s",
        "width" | "height" => "m",
        "density" => "kg/m³",
        "mass" => "kg/m²",
        "velocity" | "base_velocity" | "slip_rate_threshold" | "normal_velocity" => "m/s",
        "gravity" => "m/s²",
        _ => return None,
    })
}

/// `key (unit)`, or the key alone where its unit is not known.
pub fn with_unit(key: &str) -> String {
    match unit_of(key) {
        Some(unit) => format!("{key} ({unit})"),
        None => key.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every key of docs/cases.md's tables with a unit column (`| key | ... | unit |`) that names
    /// one unit per key, or one for all its keys, has that unit here; keys whose value is a
    /// name, not a number, are left out.
    #[test]
    fn units_agree_with_the_case_reference() {
        let docs = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/cases.md")).unwrap();
        let names = ["fixed", "group", "file", "integrator", "rstar_law", "kind", "axisymmetric", "normal"];
        let (mut in_unit_table, mut checked) = (false, 0);
        for line in docs.lines() {
            let cells: Vec<&str> = line.trim().trim_matches('|').split(" | ").map(str::trim).collect();
            if !line.starts_with('|') {
                in_unit_table = false;
                continue;
            }
            if cells[0] == "key" {
                in_unit_table = cells.get(2) == Some(&"unit");
                continue;
            }
            if !in_unit_table || !cells[0].starts_with('`') {
                continue;
            }
            let keys: Vec<&str> = cells[0].split(", ").map(|k| k.trim_matches('`')).collect();
            let units: Vec<&str> = cells[2].split(", ").collect();
            if units.iter().any(|u| u.is_empty() || u.contains('(')) {
                continue;
            }
            for (i, key) in keys.iter().enumerate() {
                if key.starts_with('[') || names.contains(key) {
                    continue;
                }
                let unit = match units.len() {
                    1 => units[0],
                    n if n == keys.len() => units[i],
                    _ => continue,
                };
                assert_eq!(unit_of(key), Some(unit), "{key} in: {line}");
                checked += 1;
            }
        }
        assert!(checked >= 30, "only {checked} keys found in docs/cases.md's unit tables");
    }

    #[test]
    fn a_nested_key_takes_its_quantitys_unit() {
        assert_eq!(with_unit("scene.normal_traction.left"), "scene.normal_traction.left (Pa)");
        assert_eq!(with_unit("scene.normal_traction.x"), "scene.normal_traction.x (m)");
        assert_eq!(with_unit("scene.phases.1.velocity"), "scene.phases.1.velocity (m/s)");
        assert_eq!(with_unit("friction.m"), "friction.m (-)");
        assert_eq!(with_unit("time.tolerance"), "time.tolerance");
    }
}
