//! Friction against a meshed obstacle (implicit Euler): the incline of `incline.rs` with the
//! ground a plate of two triangles read from an OBJ file (`[[obstacles]] shape = "mesh"`).
//! The block slides with the acceleration `g (sin(theta) - mu cos(theta))` above the
//! friction angle and sticks below it (creeping by less than `epsv` per step plus its
//! elastic shear); and on a level plate moving at a constant speed the block, at rest at the
//! start, is dragged up to the plate's speed and then carried along, slipping by less than
//! `epsv` per step; the plate's own `[[contact.obstacles]]` coefficient applies. No accepted
//! state has a block triangle intersect a plate triangle (checked by [`slide`]).

use super::incline::{assert_kinetic_acceleration, assert_sticks, slide, G};
use isochor_scenes::resolve::{self, ResolvedScene};
use isochor_scenes::Scene;

/// The barrier's reach (m); the block starts half of it above the plate.
pub const DHAT: f64 = 1e-4;
/// The time step (s) and the number of steps.
pub const DT: f64 = 0.005;
const STEPS: usize = 20;

/// The OBJ square `[-0.05, 0.1] x [-0.05, 0.07]` at `z = 0` in a scratch folder.
pub fn plate_file() -> String {
    let dir = std::env::temp_dir().join(format!("isochor-mesh-friction-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("plate.obj");
    std::fs::write(
        &path,
        "v -0.05 -0.05 0\nv 0.1 -0.05 0\nv 0.1 0.07 0\nv -0.05 0.07 0\nf 1 2 3\nf 1 3 4\n",
    )
    .unwrap();
    path.display().to_string()
}

/// The 20 x 20 x 10 mm block of the built-in incline on the meshed plate, under gravity
/// tilted by `theta` (degrees), friction `mu`, the plate translating by `translate` over the
/// run.
fn block_on_meshed_plate(theta: f64, mu: f64, translate: [f64; 3]) -> ResolvedScene {
    let friction = format!("friction = {mu}");
    resolve::build(&block_on_meshed_plate_scene(
        theta, "", &friction, translate,
    ))
    .unwrap()
}

/// The scene of [`block_on_meshed_plate`] with the `[[obstacles]]` tables `before` ahead of
/// the plate's and the `[contact]` friction keys `friction`, over [`STEPS`] steps.
fn block_on_meshed_plate_scene(
    theta: f64,
    before: &str,
    friction: &str,
    translate: [f64; 3],
) -> Scene {
    let [x, y, z] = translate;
    let ground = format!(
        "{before}[[obstacles]]\nshape = \"mesh\"\npath = '{}'\ntranslate = [{x}, {y}, {z}]\n",
        plate_file()
    );
    block_scene(theta, &ground, DHAT / 2.0, friction, STEPS)
}

/// The block of the built-in incline with its bottom at `z = bottom` over the `[[obstacles]]`
/// tables `ground`, under gravity tilted by `theta` (degrees), with `dhat` = [`DHAT`], the
/// `[contact]` friction keys `friction`, and `frames` implicit Euler steps of [`DT`].
pub fn block_scene(theta: f64, ground: &str, bottom: f64, friction: &str, frames: usize) -> Scene {
    let t = theta.to_radians();
    let text = format!(
        r#"name = "block-on-the-incline"
method = "standard"

[mesh]
generator = "box"
min = [0.0, 0.0, {bottom}]
max = [0.02, 0.02, {top}]
cells = [2, 2, 1]
res = 1

[material]
young = 1e6
nu = 0.3
rho = 1000.0

[loads]
gravity = [{gx}, 0.0, {gz}]

{ground}
[contact]
dhat = {DHAT}
self = false
{friction}

[stepping]
mode = "dynamic"
dt = {DT}
frames = {frames}
"#,
        top = bottom + 0.01,
        gx = G * t.sin(),
        gz = -G * t.cos(),
    );
    Scene::from_toml_str(&text, "block-on-the-incline").unwrap()
}

#[test]
fn the_block_slides_down_a_meshed_plate_with_the_kinetic_acceleration() {
    assert_kinetic_acceleration("meshed plate", |theta, mu| {
        block_on_meshed_plate(theta, mu, [0.0; 3])
    });
}

#[test]
fn the_block_sticks_on_a_meshed_plate_below_the_friction_angle() {
    assert_sticks("meshed plate", |theta, mu| {
        block_on_meshed_plate(theta, mu, [0.0; 3])
    });
}

/// `[[contact.obstacles]]` names the plate by its index among all `[[obstacles]]` (an
/// analytic half-space far below comes first): its coefficient holds the block at 30 degrees
/// although the scene's is 0, and the half-space keeps the scene's.
#[test]
fn the_plates_own_coefficient_holds_the_block() {
    let scene = block_on_meshed_plate_scene(
        30.0,
        "[[obstacles]]\nshape = \"half-space\"\npoint = [0.0, 0.0, -1.0]\n",
        "friction = 0.0\n[[contact.obstacles]]\nobstacle = 1\nfriction = 0.7",
        [0.0; 3],
    );
    let resolved = resolve::build(&scene).unwrap();
    let friction = resolved.friction.as_ref().unwrap();
    assert_eq!(friction.obstacles, [0.0], "the half-space's");
    let surfaces = friction.surfaces.as_ref().unwrap();
    // The block is body 0, the plate (the first meshed obstacle) body 1.
    assert_eq!(surfaces.coefficient(0, 1), 0.7);
    assert_eq!(surfaces.coefficient(0, 0), 0.0);
    let epsv = friction.epsv;
    let (path, _) = slide(resolved, None);
    let creep = path.last().unwrap().1 - path[0].1;
    let shear = 1000.0 * G * 0.5 * 0.01f64.powi(2) / (2.0 * 1e6 / 2.6);
    let bound = STEPS as f64 * epsv + shear;
    eprintln!("plate's own coefficient 0.7: displacement {creep:.3e} (bound {bound:.3e})");
    assert!(creep.abs() <= bound, "{creep} beyond {bound}");
}

#[test]
fn a_moving_meshed_plate_carries_the_block_at_its_speed() {
    let (speed, mu) = (0.05, 0.5);
    let duration = DT * STEPS as f64;
    let resolved = block_on_meshed_plate(0.0, mu, [speed * duration, 0.0, 0.0]);
    let epsv = resolved.friction.as_ref().unwrap().epsv;
    let (path, lags) = slide(resolved, None);
    // Dragged at mu g from rest, the block reaches the plate's speed after v / (mu g) = 10 ms
    // (two steps); over the second half of the run it is carried along.
    let half = path.len() / 2;
    let (t0, x0) = path[half];
    let (t1, x1) = *path.last().unwrap();
    let carried = x1 - x0;
    let plate = speed * (t1 - t0);
    let steps = (path.len() - 1 - half) as f64;
    let kinetic = speed * duration - speed * speed / (2.0 * mu * G);
    eprintln!(
        "moving meshed plate: block moved {carried:.4e} while the plate moved {plate:.4e} over the second half (slip bound {:.1e}); over the run {:.4e} (kinetic drag from rest predicts {kinetic:.4e}); lags per step {lags:?}",
        steps * epsv,
        x1 - path[0].1
    );
    assert!(
        (carried - plate).abs() <= steps * epsv,
        "the block moved {carried} with the plate's {plate}"
    );
}
