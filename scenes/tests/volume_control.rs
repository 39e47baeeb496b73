//! A chamber held at a volume (`volume_ratio` on `[[loads.pressure]]`) through the `isochor`
//! binary: its pressure and volume ratio in steps.csv, every probe at every step in
//! probes.csv, the probes of a pressure load, the pressure-volume plot, and the errors of the
//! keys.

use crate::common::{isochor, scratch, stderr, stdout};
use std::path::Path;

/// A tube chamber (the inflated tube at res 1) whose `[[loads.pressure]]` loads the faces of
/// `selection` with the keys `keys`.
fn scene(dir: &Path, selection: &str, keys: &str) -> String {
    let text = format!(
        r#"
name = "tube-volume"
method = "mixed-p1"

[mesh]
generator = "tube"
inner_radius = 0.03
outer_radius = 0.05
height = 0.12
res = 1

[material]
young = 90e3
nu = 0.499

[selections.ends]
plane = {{ point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }}

[selections.top]
plane = {{ point = [0.0, 0.0, 0.12], normal = [0.0, 0.0, 1.0] }}

[selections.inner]
radial = {{ max = 0.03 }}

[selections.outer]
radial = {{ min = 0.05 }}

[[dirichlet]]
selection = "ends"
axes = "xyz"

[[dirichlet]]
selection = "top"
axes = "xyz"

[[loads.pressure]]
selection = "{selection}"
{keys}

[stepping]
mode = "quasi-static"
steps = 2

[probes.p]
kind = "load-pressure"
load = 0

[probes.v]
kind = "enclosed-volume-ratio"
load = 0

[probes.turn]
kind = "rotation"
selection = "outer"
axis = [0.0, 0.0, 1.0]
"#
    );
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// Held at 1.2 times its rest volume in two steps: the pressure is solved for (positive: it
/// inflates), the volume ratio is the target at each step, in steps.csv, probes.csv and the
/// probes; the plot is written.
#[test]
fn a_chamber_held_at_a_volume_reports_its_pressure_at_every_step() {
    let dir = scratch("volume-control");
    let path = scene(
        &dir,
        "inner",
        "volume_ratio = 1.2\norigin = [0.0, 0.0, 0.0]",
    );
    let out = dir.join("out");
    let o = isochor(&["run", &path, "--out", out.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let (p, v) = (
        json["probes"]["p"].as_f64().unwrap(),
        json["probes"]["v"].as_f64().unwrap(),
    );
    assert!(p > 0.0, "{p}");
    assert!((v - 1.2).abs() < 1e-6, "{v}");
    // The tube's Kuhn split is chiral: inflating it twists the outer wall by a fraction of a
    // degree (0.20 measured) about its axis.
    let turn = json["probes"]["turn"].as_f64().unwrap();
    assert!(turn.abs() < 1.0, "{turn}");
    let steps = std::fs::read_to_string(out.join("steps.csv")).unwrap();
    let header: Vec<&str> = steps.lines().next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (pc, vc) = (column("pressure_0"), column("enclosed_volume_ratio_0"));
    let rows: Vec<Vec<f64>> = steps
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|c| c.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    assert_eq!(rows.len(), 2);
    assert!((rows[0][vc] - 1.1).abs() < 1e-6 && (rows[1][vc] - 1.2).abs() < 1e-6);
    assert!(0.0 < rows[0][pc] && rows[0][pc] < rows[1][pc] && rows[1][pc] == p);
    let probes = std::fs::read_to_string(out.join("probes.csv")).unwrap();
    let lines: Vec<&str> = probes.lines().collect();
    assert_eq!(lines[0], "step,t,load_level,p,turn,v");
    assert_eq!(lines.len(), 3);
    assert!(lines[1].starts_with("1,5e-1,5e-1,"), "{}", lines[1]);
    assert!(out.join("pressure-volume.png").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// With `cap_openings`, the tube's two open ends are capped: the volume held is the chamber's
/// own (about any origin), so a different pressure holds it at 1.2 than without caps (where
/// the cones from the origin to the openings count in the rest volume).
#[test]
fn capped_openings_hold_the_chambers_own_volume() {
    let dir = scratch("volume-control-capped");
    let pressure = |keys: &str| {
        let path = scene(&dir, "inner", keys);
        let o = isochor(&["run", &path, "--json"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let json: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
        assert!((json["probes"]["v"].as_f64().unwrap() - 1.2).abs() < 1e-6);
        json["probes"]["p"].as_f64().unwrap()
    };
    let capped = pressure("volume_ratio = 1.2\ncap_openings = true\norigin = [0.3, 0.1, 0.5]");
    let also_capped = pressure("volume_ratio = 1.2\ncap_openings = true");
    let open = pressure("volume_ratio = 1.2");
    assert!(
        (capped - also_capped).abs() < 1e-6 * capped,
        "{capped} {also_capped}"
    );
    assert!((capped - open).abs() > 0.05 * open, "{capped} {open}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The errors of the keys name the load and the key.
#[test]
fn bad_volume_control_is_an_error_naming_the_load_and_key() {
    let dir = scratch("volume-control-errors");
    let cases = [
        (
            "inner",
            "volume_ratio = 1.2\npressure = 1e3",
            "loads.pressure.0.volume_ratio",
            "not both",
        ),
        (
            "inner",
            "volume_ratio = -1.0",
            "loads.pressure.0.volume_ratio",
            "positive",
        ),
        ("inner", "", "loads.pressure.0", "volume_ratio"),
        // The outer wall's faces point out of the body: they enclose no cavity.
        (
            "outer",
            "volume_ratio = 1.2",
            "loads.pressure.0",
            "enclose no volume",
        ),
    ];
    for (selection, load, key, words) in cases {
        let path = scene(&dir, selection, load);
        let o = isochor(&["run", &path]);
        let err = stderr(&o);
        assert!(!o.status.success(), "{load}");
        assert!(err.contains(key) && err.contains(words), "{load}: {err}");
    }
    let path = scene(&dir, "inner", "volume_ratio = 1.2");
    let o = isochor(&["run", &path, "--set", "method=dual"]);
    let err = stderr(&o);
    assert!(!o.status.success());
    assert!(
        err.contains("dual") && err.contains("volume_ratio"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
