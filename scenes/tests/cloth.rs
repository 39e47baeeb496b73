//! Cloth bodies in a scene (`[[bodies]]` with `kind = "cloth"`): a band on a rigid cylinder
//! settles on it (the scene form of the validation test `cloth_sheets::band_on_a_rigid_cylinder_carries_laplace_pressure`,
//! its numbers), and each bad input is an error naming the body, the file and the key.

use isochor_scenes::resolve::build;
use isochor_scenes::{run_scene, RunOptions, Scene, SceneError};
use std::f64::consts::PI;

/// The cylinder's radius `R` (m); the band is placed at `1.02 R`, 5 cm wide.
const RADIUS: f64 = 0.1;

/// A band of `res` cells across its width on a rigid cylinder of radius `R` (frictionless),
/// with a clamped 2 cm cube aside (a problem's mesh needs a tet); `band` is more TOML of the
/// band's `[[bodies]]` entry, `extra` more of the scene.
fn band_scene(res: usize, band: &str, extra: &str) -> String {
    format!(
        r#"name = "band-on-cylinder"
method = "standard"

[material]
young = 1e6
nu = 0.3

[[bodies]]
name = "block"
mesh = {{ generator = "box", min = [0.2, 0.0, 0.0], max = [0.22, 0.02, 0.02], res = 1 }}

[[bodies]]
name = "band"
kind = "cloth"
mesh = {{ generator = "band", radius = 0.102, width = 0.05, res = {res} }}
material = {{ young = 1e6, poisson = 0.3, thickness = 5e-4, density = 300.0 }}
rest_scale = 0.9
{band}

[[obstacles]]
shape = "cylinder"
point = [0.0, 0.0, 0.0]
axis = [0.0, 0.0, 1.0]
radius = {RADIUS}

[selections.block]
all = true
body = "block"

[selections.bottom]
plane = {{ point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }}
body = "band"

[selections.on_x]
sphere = {{ center = [0.102, 0.0, 0.0], radius = 1e-4 }}
body = "band"

[selections.middle]
plane = {{ point = [0.0, 0.0, {mid}], normal = [0.0, 0.0, 1.0] }}
body = "band"

[[dirichlet]]
selection = "block"

# The bottom ring held axially (the band contracts freely across its width), its vertex on
# the x axis tangentially (the rotation about the axis).
[[dirichlet]]
selection = "bottom"
axes = "z"

[[dirichlet]]
selection = "on_x"
axes = "y"

[probes.waistband_circumference]
kind = "loop-length"
selection = "middle"

[stepping]
mode = "quasi-static"
steps = 1

{extra}
"#,
        mid = 0.05 * (res / 2) as f64 / res as f64
    )
}

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::from_toml_str(text, "test scene")
}

/// At 2 cells across (26 around, 104 triangles) the band settles on the cylinder: its middle
/// loop, a polygon of 26 sides, is the one inscribed in the circle of radius `R` to 1e-5 (the
/// library test's tolerance on the mean radius), though placed at `1.02 R`.
#[test]
fn a_band_settles_on_a_rigid_cylinder() {
    let scene = parse(&band_scene(2, "", "")).unwrap();
    let resolved = build(&scene).unwrap();
    assert_eq!(resolved.problem.cloths.len(), 1);
    assert_eq!(resolved.problem.cloths[0].triangles.len(), 104);
    let (result, _) = run_scene(&scene, &RunOptions::default()).unwrap();
    assert!(result.converged, "{:?}", result.error);
    let around = 26.0;
    let polygon = around * 2.0 * RADIUS * (PI / around).sin();
    let measured = result.probes["waistband_circumference"];
    assert!(
        (measured / polygon - 1.0).abs() < 1e-5,
        "circumference {measured} against {polygon}"
    );
}
