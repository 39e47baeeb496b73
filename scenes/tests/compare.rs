//! `isochor compare` beside published values: the `[paper]` columns, the factor lost over a
//! sweep, the display units, the tables' width, and the plots, checked on comparisons built
//! from synthetic runs (with the built-in spine arm's `[paper]` section, Table 2 of Francu
//! et al. 2021) and end to end on the coarsest cantilever.

use crate::common::{isochor_in, scratch};
use isochor_scenes::commands::compare::{CompareRow, Comparison};
use isochor_scenes::format::PaperSpec;
use isochor_scenes::format::{LengthUnit, Scene};
use isochor_scenes::{builtin, load_scene, RunResult, SceneError};
use std::collections::BTreeMap;
use std::path::Path;

/// The probe of the spine arm's `[paper]` section.
const PROBE: &str = "tip_deflection";

/// A run of `method` with the given probe values (converged or not).
fn result(method: &str, probes: &[(&str, f64)], converged: bool) -> RunResult {
    RunResult {
        scene: "spine-arm".into(),
        variant: None,
        method: method.into(),
        element: "tet4".into(),
        nu: 0.49,
        vertices: 10,
        nodes: 10,
        tets: 1260,
        dofs: 100,
        steps: 1,
        steps_requested: 1,
        newton_iterations: 5,
        cuts: 0,
        converged,
        wall_time_s: 0.5,
        timings: Default::default(),
        volume_change: -1e-3,
        probes: probes.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
        max_inverted_tets: 0,
        constraint_residual: 0.0,
        error: None,
        failed_step: None,
        overrides: Vec::new(),
        warnings: Vec::new(),
        history: Vec::new(),
        failed: None,
        dynamic: false,
        obstacles: Vec::new(),
        body_pairs: Vec::new(),
    }
}

/// The spine arm's published values.
fn table_2() -> PaperSpec {
    load_scene("spine-arm", None, &[])
        .unwrap()
        .paper
        .expect("spine-arm has a [paper] section")
}

/// A comparison of `standard` and `mixed-p1` over `key = values` on the spine arm (tip
/// deflection in cm), with tip deflections `tips[config][i]`.
fn comparison(key: Option<&str>, values: &[&str], tips: [&[f64]; 2]) -> Comparison {
    let mut rows = Vec::new();
    for (i, v) in values.iter().enumerate() {
        for (label, tips) in ["standard", "mixed-p1"].into_iter().zip(tips) {
            rows.push(CompareRow {
                sweep_value: key.map(|_| v.to_string()),
                label: label.into(),
                result: Ok(result(label, &[(PROBE, tips[i])], true)),
            });
        }
    }
    Comparison {
        scene: "spine-arm".into(),
        sweep_key: key.map(str::to_string),
        rows,
        paper: Some(table_2()),
        units: BTreeMap::from([(PROBE.to_string(), LengthUnit::Centimetre)]),
    }
}

/// The sweep of Table 2.
const NUS: [&str; 4] = ["0.49", "0.499", "0.4999", "0.49999"];

/// The cells of the text table's rows (lines whose first cell is a swept value).
fn rows_of(text: &str, header: &str) -> Vec<Vec<String>> {
    let mut lines = text.lines().skip_while(|l| !l.starts_with(header));
    lines.next().expect("the table's header");
    lines
        .take_while(|l| !l.is_empty())
        .map(|l| l.split_whitespace().map(str::to_string).collect())
        .collect()
}

/// Each run shows Table 2's value for its method and nu beside its own, both in centimetres
/// (the scene's display unit), in the text and Markdown tables; compare.csv and compare.json
/// carry the same published values in metres, and every printed line fits in 100 columns.
#[test]
fn paper_columns_show_the_scenes_values() {
    let paper = table_2();
    let standard = [0.06, 0.015, 0.007, 0.006];
    let mixed = [0.132, 0.129, 0.1287, 0.1287];
    let c = comparison(Some("nu"), &NUS, [&standard, &mixed]);
    let text = c.to_text();
    assert!(text.contains("tip_deflection (cm)  paper"), "{text}");
    let rows = rows_of(&text, "nu ");
    assert_eq!(rows.len(), 8, "{text}");
    let header: Vec<&str> = text
        .lines()
        .find(|l| l.starts_with("nu "))
        .unwrap()
        .split("  ")
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .collect();
    let ours = header
        .iter()
        .position(|h| *h == "tip_deflection (cm)")
        .unwrap();
    let published = header.iter().position(|h| *h == "paper").unwrap();
    for (i, row) in rows.iter().enumerate() {
        let (nu, label) = (NUS[i / 2], ["standard", "mixed-p1"][i % 2]);
        assert_eq!((row[0].as_str(), row[1].as_str()), (nu, label), "{text}");
        let tip = [standard, mixed][i % 2][i / 2];
        let expected = paper.probes[PROBE][label][i / 2];
        let shown: f64 = row[published].parse().unwrap();
        // Four significant digits of a value in centimetres.
        assert!(
            (shown - 100.0 * expected).abs() <= 5e-4 * 100.0 * expected,
            "{text}"
        );
        let own: f64 = row[ours].parse().unwrap();
        assert!((own - 100.0 * tip).abs() <= 5e-4 * 100.0 * tip, "{text}");
    }
    assert!(text.lines().all(|l| l.len() <= 100), "{text}");
    assert!(text.contains("Francu et al. 2021, Table 2"), "{text}");
    let markdown = c.to_markdown();
    assert!(
        markdown.contains("| tip_deflection (cm) | paper |"),
        "{markdown}"
    );

    let csv = c.to_csv();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header
        .iter()
        .position(|h| *h == "paper:tip_deflection")
        .unwrap();
    assert_eq!(column, header.len() - 1, "paper columns come last: {csv}");
    for (i, line) in lines.enumerate() {
        let label = ["standard", "mixed-p1"][i % 2];
        let cell: f64 = line.split(',').nth(column).unwrap().parse().unwrap();
        let expected = paper.probes[PROBE][label][i / 2];
        assert!((cell - expected).abs() <= 1e-6 * expected, "{csv}");
    }
    let json = c.to_json();
    for (i, run) in json["runs"].as_array().unwrap().iter().enumerate() {
        let label = ["standard", "mixed-p1"][i % 2];
        assert_eq!(run["paper"][PROBE], paper.probes[PROBE][label][i / 2]);
        assert_eq!(run["probes"][PROBE], [standard, mixed][i % 2][i / 2]);
    }
    assert_eq!(json["units"][PROBE], "cm");
}

/// The factor is the probe's value at the first swept value over its value at the last,
/// ours and the paper's (Table 2: 11.2 / 0.8 = 14 for standard, 14.6 / 13.8 for mixed-p1);
/// a run that did not converge has none.
#[test]
fn the_factor_is_the_first_value_over_the_last() {
    let c = comparison(
        Some("nu"),
        &NUS,
        [&[0.08, 0.04, 0.02, 0.01], &[0.15, 0.15, 0.15, 0.12]],
    );
    let factors = c.factors();
    let of = |label: &str| factors.iter().find(|f| f.label == label).unwrap();
    assert_eq!(of("standard").ours, Some(0.08 / 0.01));
    assert_eq!(of("mixed-p1").ours, Some(0.15 / 0.12));
    assert_eq!(of("standard").paper, Some(0.112 / 0.008));
    assert_eq!(of("mixed-p1").paper, Some(0.146 / 0.138));
    let text = c.to_text();
    let rows = rows_of(&text, "config ");
    assert_eq!(
        rows,
        [
            ["standard", "8.00x", "14.00x"].map(String::from),
            ["mixed-p1", "1.25x", "1.06x"].map(String::from)
        ],
        "{text}"
    );
    assert_eq!(c.to_json()["factors"][0]["ours"], 0.08 / 0.01);

    let mut c = c;
    let last = c.rows.len() - 2;
    if let Ok(r) = &mut c.rows[last].result {
        r.converged = false;
    }
    let factors = c.factors();
    let standard = factors.iter().find(|f| f.label == "standard").unwrap();
    assert_eq!(standard.ours, None);
    assert_eq!(standard.paper, Some(0.112 / 0.008));
    // One swept value has no factor.
    assert!(comparison(Some("nu"), &NUS[..1], [&[0.1], &[0.1]])
        .factors()
        .is_empty());
}

/// Published values are shown only beside runs that sweep the paper's key, at values the
/// paper gives: another key, or none of its values, is reported as not matching (no paper
/// column, nothing in the CSV or JSON); a partial match shows what matches and names the rest.
#[test]
fn a_paper_sweep_that_does_not_match_is_reported() {
    let no_paper = |c: &Comparison| {
        let text = c.to_text();
        assert!(text.lines().all(|l| l.len() <= 100), "{text}");
        assert!(c.paper_probes().is_empty());
        assert!(!text.contains("  paper"), "{text}");
        assert!(!c.to_csv().contains("paper:"));
        let json = c.to_json();
        assert!(json["runs"]
            .as_array()
            .unwrap()
            .iter()
            .all(|r| r.get("paper").is_none()));
        assert!(json["factors"]
            .as_array()
            .unwrap()
            .iter()
            .all(|f| f["paper"].is_null()));
        // The notes are wrapped to 100 columns: read them as one line.
        text.split_whitespace().collect::<Vec<_>>().join(" ")
    };
    let other_key = comparison(Some("E"), &["100e3", "200e3"], [&[0.1, 0.05], &[0.1, 0.05]]);
    let text = no_paper(&other_key);
    assert!(text.contains("not over E: cannot match"), "{text}");
    let other_values = comparison(Some("nu"), &["0.3", "0.4"], [&[0.1, 0.05], &[0.1, 0.05]]);
    let text = no_paper(&other_values);
    assert!(
        text.contains("none of those values: cannot match"),
        "{text}"
    );
    let unswept = comparison(None, &["-"], [&[0.1], &[0.1]]);
    let text = no_paper(&unswept);
    assert!(text.contains("sweep nu to see"), "{text}");

    // The dotted key is the same parameter; 0.45 is not in Table 2.
    let partial = comparison(
        Some("material.nu"),
        &["0.45", "0.49"],
        [&[0.1, 0.05], &[0.1, 0.05]],
    );
    let text = partial.to_text();
    assert!(text.contains("no values at material.nu = 0.45"), "{text}");
    let paper: Vec<Option<f64>> = partial
        .rows
        .iter()
        .map(|r| partial.paper_value(r, PROBE))
        .collect();
    assert_eq!(paper, [None, None, Some(0.112), Some(0.146)]);
}

/// Tables wider than 100 columns are split into several, each repeating the swept value and
/// the label, so that every probe is printed.
#[test]
fn wide_tables_are_split_to_100_columns() {
    let probes: Vec<String> = (0..8).map(|i| format!("a_long_probe_name_{i}")).collect();
    let values: Vec<(&str, f64)> = probes.iter().map(|p| (p.as_str(), 1.5)).collect();
    let rows = NUS
        .iter()
        .map(|nu| CompareRow {
            sweep_value: Some(nu.to_string()),
            label: "standard".into(),
            result: Ok(result("standard", &values, true)),
        })
        .collect();
    let c = Comparison {
        scene: "wide".into(),
        sweep_key: Some("nu".into()),
        rows,
        paper: None,
        units: BTreeMap::new(),
    };
    let text = c.to_text();
    assert!(text.lines().all(|l| l.len() <= 100), "{text}");
    for p in &probes {
        assert!(text.contains(p.as_str()), "{text}");
    }
    assert!(text.matches("nu       config").count() >= 2, "{text}");
}

/// The spine arm's text with `from` replaced by `to`, parsed.
fn spine_arm_with(from: &str, to: &str) -> Result<Scene, SceneError> {
    let text = builtin::builtin("spine-arm").unwrap();
    assert!(text.contains(from), "{from}");
    Scene::from_toml_str(&text.replacen(from, to, 1), "test")
}

/// Bad keys and values of `[paper]` and of a probe's `unit` are errors naming the key.
#[test]
fn bad_paper_keys_are_named() {
    let cases = [
        ("sweep = \"nu\"", "sweeps = \"nu\"", "sweeps"),
        (
            "[paper.probes.tip_deflection]",
            "[paper.probes.tip]",
            "paper.probes.tip",
        ),
        (
            "mixed-p1 = [0.146",
            "mixed = [0.146",
            "paper.probes.tip_deflection.mixed",
        ),
        (
            "standard = [0.112, 0.063, 0.024, 0.008]",
            "standard = [0.112, 0.063, 0.024]",
            "paper.probes.tip_deflection.standard",
        ),
        (
            "values = [0.49, 0.499,",
            "values = [0.49, 0.49,",
            "paper.values.1",
        ),
        // The probe's kind tags its table, so the deserializer names the probe, not the key.
        (
            "unit = \"cm\"",
            "unit = \"inch\"",
            "probes.tip_deflection': unknown value `inch`",
        ),
        // A probe that is not a length takes no unit.
        (
            "kind = \"volume-change\"",
            "kind = \"volume-ratio\"\nunit = \"cm\"",
            "unknown field `unit`",
        ),
    ];
    for (from, to, key) in cases {
        let e = spine_arm_with(from, to).expect_err(to).to_string();
        assert!(e.contains(key), "{to}: {e}");
    }
}

/// The width and height of a PNG file.
fn png_size(path: &Path) -> (u32, u32) {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap();
    (reader.info().width, reader.info().height)
}

/// A sweep writes compare.png (one 500-pixel panel per probe but the volume change) and compare-residuals.png into
/// `--out`, or without it into `compare-SCENE` in the working directory, and says where.
#[test]
fn plots_are_png_files_written_where_said() {
    let dir = scratch("compare-plots");
    let args = [
        "compare",
        "cantilever",
        "--methods",
        "standard,mixed-p1",
        "--set",
        "res=1",
        "--set",
        "steps=2",
        "--sweep",
        "nu=0.49,0.4999",
    ];
    let o = isochor_in(&args, &dir);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let default = Path::new("compare-cantilever");
    for file in ["compare.csv", "compare.png", "compare-residuals.png"] {
        let said = default.join(file).display().to_string();
        assert!(stdout.contains(&said), "{said}: {stdout}");
    }
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join(default).join("compare.json")).unwrap(),
    )
    .unwrap();
    let probes = json["runs"][0]["probes"].as_object().unwrap();
    let panels = probes.keys().filter(|k| *k != "volume_change").count() as u32;
    assert_eq!(
        png_size(&dir.join(default).join("compare.png")),
        (1000, 500 * panels)
    );
    assert_eq!(
        png_size(&dir.join(default).join("compare-residuals.png")),
        (1000, 500)
    );

    let out = dir.join("out");
    let mut with_out = args.to_vec();
    with_out.extend(["--out", out.to_str().unwrap()]);
    let o = isochor_in(&with_out, &dir);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains(&out.join("compare.png").display().to_string()),
        "{stdout}"
    );
    assert_eq!(png_size(&out.join("compare.png")), (1000, 500 * panels));
    assert_eq!(png_size(&out.join("compare-residuals.png")), (1000, 500));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A comparison of dynamic runs also writes compare-energy.png: three 500-pixel panels (total
/// energy, potential energy, volume change against time); a static one does not.
#[test]
fn dynamic_comparisons_plot_the_energies_against_time() {
    let dir = scratch("compare-energy");
    let out = dir.join("out");
    let args = [
        "compare",
        "dynamic-cube",
        "--variants",
        "zonal,global-rescale",
        "--set",
        "res=2",
        "--set",
        "frames=3",
        "--out",
        out.to_str().unwrap(),
    ];
    let o = isochor_in(&args, &dir);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(png_size(&out.join("compare-energy.png")), (1000, 1500));
    let statics = dir.join("statics");
    let args = [
        "compare",
        "cantilever",
        "--methods",
        "standard",
        "--set",
        "res=1",
        "--out",
        statics.to_str().unwrap(),
    ];
    let o = isochor_in(&args, &dir);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!statics.join("compare-energy.png").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
