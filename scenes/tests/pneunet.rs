//! A user's own soft robot: the PneuNet-style actuator of the test data (`pneunet-v41.msh`,
//! Gmsh output: a 0.10 x 0.02 x 0.015 m block along x with four chambers joined by a channel,
//! surface groups `base` at x = 0 and `chamber`), clamped on `base`, its chambers
//! pressurized, in silicone fitted by Mooney-Rivlin (and the other models).

use isochor_scenes::{load_scene, run_scene, Override, RunOptions, RunResult};
use std::path::Path;

/// Silicone fitted by Mooney-Rivlin: initial shear modulus 2 (c10 + c01) = 35.2 kPa.
const MOONEY_RIVLIN: &str = "model = \"mooney-rivlin\"\nc10 = 16e3\nc01 = 1.6e3";

/// The actuator in `material` (the stiffness keys of `[material]`) with `sets` applied.
fn pneunet(material: &str, sets: &[&str]) -> RunResult {
    let mesh = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pneunet-v41.msh");
    let text = format!(
        r#"name = "pneunet"
method = "mixed-p1"

[mesh]
generator = "file"
path = {mesh:?}

[material]
{material}
nu = 0.49
rho = 1070.0

[selections.base]
physical = "base"

[selections.chamber]
physical = "chamber"

[selections.tip]
plane = {{ point = [0.10, 0.0, 0.0], normal = [1.0, 0.0, 0.0] }}

[[dirichlet]]
selection = "base"

[[loads.pressure]]
selection = "chamber"
pressure = 3e3

[stepping]
mode = "quasi-static"
steps = 1

[probes.tip_x]
kind = "displacement"
selection = "tip"
component = "x"

[probes.tip_z]
kind = "displacement"
selection = "tip"
component = "z"
"#
    );
    let dir = std::env::temp_dir().join(format!(
        "isochor-pneunet-{}-{}",
        std::process::id(),
        material.len() + sets.len()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("pneunet.toml");
    std::fs::write(&path, text).unwrap();
    let overrides: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    let scene = load_scene(path.to_str().unwrap(), None, &overrides).unwrap();
    let (result, _) = run_scene(&scene, &RunOptions::default()).unwrap();
    assert!(result.converged, "{sets:?}: {:?}", result.error);
    result
}

/// Inflated, the actuator bends: its chambers sit above the mid-plane, so the top lengthens
/// more than the bottom and the tip moves down (-z) several times farther than it moves out
/// (+x). Mooney-Rivlin with the neo-Hookean's initial shear modulus bends alike at this
/// moderate strain (within 10%).
#[test]
fn the_pneunet_bends_when_its_chambers_are_pressurized() {
    let mr = pneunet(MOONEY_RIVLIN, &[]);
    let (x, z) = (mr.probes["tip_x"], mr.probes["tip_z"]);
    eprintln!(
        "Mooney-Rivlin: tip x {x:e}, z {z:e}, {} Newton iterations, {:.2} s",
        mr.newton_iterations, mr.wall_time_s
    );
    assert!(z < -1e-3 && z < -2.0 * x.abs(), "tip x {x:e}, z {z:e}");
    assert!(x > 0.0, "the top lengthens: tip x {x:e}");
    let nh = pneunet("mu = 35.2e3", &[]);
    let z_nh = nh.probes["tip_z"];
    eprintln!("neo-Hookean: tip z {z_nh:e}");
    assert!((z / z_nh - 1.0).abs() < 0.1, "{z:e} vs {z_nh:e}");
}

/// The same actuator on 10-node tets (Taylor-Hood P2-P1), run with `--ignored` (30 s in the
/// test profile). Measured 2026-11-30: the tip moves 1.048 mm down in 6 Newton iterations,
/// against 1.817 mm on the 4-node tets of the same mesh: the linear tets bend the actuator
/// more, not less, here. Not a load error: at 30 Pa and `nu = 0.3` (linear response, no
/// locking) the quadratic mesh takes 1.63 times the load work of the linear one, as the
/// larger space must (`standard`: 6.88e-7 J against 4.21e-7 J), in ballooning chamber walls,
/// while its tip moves less (22.2 um against 25.2 um). Which tip value is nearer the
/// converged one needs a refinement study of this geometry (not yet done).
#[test]
#[ignore]
fn the_pneunet_bends_on_quadratic_tets() {
    let mr = pneunet(MOONEY_RIVLIN, &["element=tet10"]);
    let z = mr.probes["tip_z"];
    eprintln!(
        "tet10 Mooney-Rivlin: tip z {z:e}, {} Newton iterations, {:.2} s",
        mr.newton_iterations, mr.wall_time_s
    );
    assert!(z < -1e-3, "tip z {z:e}");
}
