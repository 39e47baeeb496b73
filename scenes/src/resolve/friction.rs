//! `[contact]`'s friction keys in the solver's terms: one coefficient per obstacle, the
//! coefficients between bodies, the slip length.

use super::bodies::SceneBodies;
use crate::format::{ContactSpec, DEFAULT_EPSV};
use isochor_solvers::{FrictionSpec, SurfaceFrictionSpec};

/// The friction of `contact` for a scene of `bodies` (over `num_nodes` nodes) whose
/// analytic obstacles are the `[[obstacles]]` entries `analytic` (in the solver's order),
/// with barrier reach `dhat`; `None` when every coefficient is 0 (the scene is then
/// frictionless, exactly as without the keys).
pub fn friction(
    contact: &ContactSpec,
    bodies: &SceneBodies,
    num_nodes: usize,
    analytic: &[usize],
    dhat: f64,
) -> Option<FrictionSpec> {
    let obstacles: Vec<f64> = analytic
        .iter()
        .map(|&k| {
            contact
                .obstacles
                .iter()
                .rev()
                .find(|o| o.obstacle == k)
                .map_or(contact.friction, |o| o.friction)
        })
        .collect();
    let index = |name: &str| bodies.names.iter().position(|n| n == name);
    let pairs: Vec<([usize; 2], f64)> = contact
        .pairs
        .iter()
        .filter_map(|p| Some(([index(&p.bodies[0])?, index(&p.bodies[1])?], p.friction)))
        .collect();
    let surfaces =
        (contact.friction > 0.0 || pairs.iter().any(|p| p.1 > 0.0)).then(|| SurfaceFrictionSpec {
            friction: contact.friction,
            pairs,
            node_bodies: bodies.node_bodies(num_nodes),
        });
    let any_obstacle = obstacles.iter().any(|&mu| mu > 0.0);
    (any_obstacle || surfaces.is_some()).then(|| FrictionSpec {
        epsv: contact.epsv.unwrap_or(DEFAULT_EPSV * dhat),
        obstacles,
        surfaces,
    })
}
