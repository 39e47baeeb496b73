//! Checks of a scene that its types cannot express: every number finite, supports that hold
//! a quasi-static body, obstacles clear of the body at the start.

use crate::scene::{ObstacleSpec, Scene};
use crate::SceneError;
use isochor_solvers::Problem;
use toml::Value;

/// Refuses NaN anywhere in a scene's TOML tree, and infinities except where a key accepts
/// one (`radial.max`), naming the key (`loads.gravity[1]`).
pub fn finite_numbers(tree: &Value, origin: &str) -> Result<(), SceneError> {
    let mut path = String::new();
    walk(tree, &mut path).map_err(|(key, message)| SceneError::Invalid {
        origin: origin.to_string(),
        key,
        message,
    })
}

fn walk(value: &Value, path: &mut String) -> Result<(), (String, String)> {
    match value {
        Value::Float(x) if x.is_nan() => Err((path.clone(), "NaN is not a number".into())),
        Value::Float(x) if x.is_infinite() && !(*x > 0.0 && path.ends_with("radial.max")) => {
            Err((path.clone(), format!("{x} is not a finite number")))
        }
        Value::Array(items) => items
            .iter()
            .enumerate()
            .try_for_each(|(i, item)| enter(path, &format!("[{i}]"), item)),
        Value::Table(table) => table.iter().try_for_each(|(key, item)| {
            let dot = if path.is_empty() { "" } else { "." };
            enter(path, &format!("{dot}{key}"), item)
        }),
        _ => Ok(()),
    }
}

/// Walks `item` with `segment` appended to `path`.
fn enter(path: &mut String, segment: &str, item: &Value) -> Result<(), (String, String)> {
    let len = path.len();
    path.push_str(segment);
    let result = walk(item, path);
    path.truncate(len);
    result
}

/// Refuses quasi-static stepping when the Dirichlet conditions leave a rigid motion free:
/// the equilibrium is singular along it.
pub fn supports(scene: &Scene, problem: &Problem) -> Result<(), SceneError> {
    if scene.is_dynamic() {
        return Ok(());
    }
    let free = problem.unremoved_rigid_modes();
    if free == 0 {
        return Ok(());
    }
    Err(SceneError::Invalid {
        origin: format!("scene {}", scene.name),
        key: "dirichlet".into(),
        message: format!(
            "quasi-static stepping needs supports that hold the body, but the Dirichlet \
             conditions leave {free} of its 6 rigid motions (3 translations, 3 rotations) free, \
             and the equilibrium is singular along them: hold more of the body (e.g. clamp a \
             face, or three nodes not on one line in every axis), add an obstacle, or use \
             dynamic stepping"
        ),
    })
}

/// Refuses an obstacle that holds nodes of the body at the start (signed distance below
/// `-tolerance` at the rest positions, `tolerance` relative to the mesh's bounding-box
/// diagonal as the contact tolerance is): contact would push them out in the first step, or
/// ignore an obstacle that lies inside the body.
pub fn obstacles_clear(scene: &Scene, problem: &Problem, tolerance: f64) -> Result<(), SceneError> {
    let nodes = problem.mesh.nodes();
    let (lo, hi) = nodes
        .iter()
        .fold((nodes[0], nodes[0]), |(lo, hi), x| (lo.inf(x), hi.sup(x)));
    let depth = tolerance * (hi - lo).norm();
    for (i, (obstacle, spec)) in problem.obstacles.iter().zip(&scene.obstacles).enumerate() {
        let (inside, deepest) = nodes
            .iter()
            .map(|x| obstacle.distance(x, 0.0).0)
            .filter(|&d| d < -depth)
            .fold((0usize, 0.0f64), |(n, deepest), d| (n + 1, deepest.min(d)));
        if inside > 0 {
            let kind = match spec {
                ObstacleSpec::HalfSpace { .. } => "half-space",
                ObstacleSpec::Sphere { .. } => "sphere",
                ObstacleSpec::Cylinder { .. } => "cylinder",
                ObstacleSpec::Ring { .. } => "ring",
            };
            return Err(SceneError::Invalid {
                origin: format!("scene {}", scene.name),
                key: format!("obstacles[{i}]"),
                message: format!(
                    "the {kind} obstacle overlaps the body at the start: {inside} of its {} \
                     nodes lie inside it (the deepest {:.3e} inside); place it clear of the \
                     rest shape and move it in with `translate`",
                    nodes.len(),
                    -deepest
                ),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str) -> Result<(), (String, String)> {
        walk(&toml::from_str(text).unwrap(), &mut String::new())
    }

    #[test]
    fn non_finite_numbers_are_named_by_key() {
        assert_eq!(
            check("[loads]\ngravity = [0, nan, 0]"),
            Err(("loads.gravity[1]".into(), "NaN is not a number".into()))
        );
        assert_eq!(
            check("[[obstacles]]\ncenter = [0, 0, 0]\n[[obstacles]]\nradius = -inf"),
            Err((
                "obstacles[1].radius".into(),
                "-inf is not a finite number".into()
            ))
        );
        assert_eq!(
            check("[mesh]\npositions = [[0, 0, 0], [1, inf, 0]]"),
            Err((
                "mesh.positions[1][1]".into(),
                "inf is not a finite number".into()
            ))
        );
        assert!(check("[selections.a.radial]\nmax = inf\nmin = 0.5").is_ok());
        assert!(check("[selections.a.radial]\nmin = inf").is_err());
    }
}
