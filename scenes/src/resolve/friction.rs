//! `[contact]`'s friction keys in the solver's terms: one coefficient per analytic obstacle,
//! the coefficients between bodies, the slip length. A meshed obstacle is one more body of
//! the surface friction (the `k`-th after the scene's `B` bodies is body `B + k`), so its
//! coefficient is a pair override between it and every body.

use super::bodies::SceneBodies;
use crate::format::{ContactSpec, DEFAULT_EPSV};
use isochor_solvers::{FrictionSpec, SurfaceFrictionSpec};

/// The friction of `contact` for a scene of `bodies` whose analytic obstacles are the
/// `[[obstacles]]` entries `analytic` and meshed ones the entries `meshed` (each in the
/// solver's order), with barrier reach `dhat`; `None` when every coefficient is 0 (the
/// scene is then frictionless, exactly as without the keys).
pub fn friction(
    contact: &ContactSpec,
    bodies: &SceneBodies,
    [analytic, meshed]: [&[usize]; 2],
    dhat: f64,
) -> Option<FrictionSpec> {
    let coefficient = |k: usize| {
        contact
            .obstacles
            .iter()
            .rev()
            .find(|o| o.obstacle == k)
            .map_or(contact.friction, |o| o.friction)
    };
    let obstacles: Vec<f64> = analytic.iter().map(|&k| coefficient(k)).collect();
    let index = |name: &str| bodies.names.iter().position(|n| n == name);
    let num_bodies = bodies.names.len();
    let body_pairs = contact
        .pairs
        .iter()
        .filter_map(|p| Some(([index(&p.bodies[0])?, index(&p.bodies[1])?], p.friction)));
    let obstacle_pairs = meshed
        .iter()
        .enumerate()
        .flat_map(|(j, &k)| (0..num_bodies).map(move |b| ([b, num_bodies + j], coefficient(k))));
    let pairs: Vec<([usize; 2], f64)> = body_pairs.chain(obstacle_pairs).collect();
    let surfaces = (contact.friction > 0.0 || pairs.iter().any(|p| p.1 > 0.0)).then_some(
        SurfaceFrictionSpec {
            friction: contact.friction,
            pairs,
        },
    );
    let any_obstacle = obstacles.iter().any(|&mu| mu > 0.0);
    (any_obstacle || surfaces.is_some()).then(|| FrictionSpec {
        epsv: contact.epsv.unwrap_or(DEFAULT_EPSV * dhat),
        obstacles,
        surfaces,
    })
}
