//! A cloth body of a scene (`kind = "cloth"`): its triangle surface generated (`band`) or
//! read (OBJ, STL, Gmsh), placed and checked, and its fabric, as the solver's [`ClothSheet`]
//! over vertices numbered from `first`.

use super::bodies::placement;
use crate::error::SceneError;
use crate::format::{BodyRef, ClothMaterialSpec, MeshSpec, Scene};
use isochor_energies::cloth::Fabric;
use isochor_mesh::io::{read_surface, TriangleSurface};
use isochor_mesh::{generate, Vec3};
use isochor_solvers::ClothSheet;
use serde::Deserialize;
use std::collections::HashMap;

/// A cloth body's placed surface and its sheet (triangles numbered from `first`).
pub struct Cloth {
    /// The placed vertices.
    pub vertices: Vec<Vec3>,
    /// The sheet, its triangles over the mesh's vertices `first..first + vertices.len()`.
    pub sheet: ClothSheet,
}

/// The cloth `body` of `scene`, its vertices to be numbered from `first`. Refuses a surface
/// with no triangles, a non-manifold edge (one of more than two triangles) or a coordinate
/// that is not finite, naming the body, the file and the key.
pub fn cloth(scene: &Scene, body: &BodyRef, first: usize) -> Result<Cloth, SceneError> {
    let invalid = |key: String, message: String| SceneError::Invalid {
        origin: format!("scene {}", scene.name),
        key,
        message: format!("cloth '{}': {message}", body.name),
    };
    let (surface, source, key) = match body.mesh {
        MeshSpec::Band { radius, width, res } => (
            generate::band(*radius, *width, *res),
            "the band generator".to_string(),
            body.key("mesh"),
        ),
        MeshSpec::File { path } => (
            read_surface(path),
            path.display().to_string(),
            body.key("mesh.path"),
        ),
        _ => {
            return Err(invalid(
                body.key("mesh"),
                "a cloth's mesh is the band generator or a surface file".into(),
            ))
        }
    };
    let surface = surface.map_err(|e| invalid(key.clone(), e.to_string()))?;
    check_surface(&surface).map_err(|m| invalid(key, format!("{source}: {m}")))?;
    let place = body.place.map(placement);
    let vertices = match place {
        Some(place) => surface.vertices.iter().map(place).collect(),
        None => surface.vertices,
    };
    let material = body.material.cloned().unwrap_or_default();
    let fabric = ClothMaterialSpec::deserialize(toml::Value::Table(material))
        .map_err(|e| invalid(body.key("material"), e.to_string()))?;
    let sheet = ClothSheet {
        name: body.name.to_string(),
        triangles: surface
            .triangles
            .iter()
            .map(|t| t.map(|v| v + first))
            .collect(),
        fabric: Fabric::new(fabric.young, fabric.poisson, fabric.thickness)?,
        density: fabric.density,
        rest_scale: body.rest_scale.unwrap_or(1.0),
    };
    Ok(Cloth { vertices, sheet })
}

/// A triangle surface: some triangles, finite coordinates, every edge on at most two
/// triangles.
fn check_surface(surface: &TriangleSurface) -> Result<(), String> {
    if surface.triangles.is_empty() {
        return Err("has no triangles".into());
    }
    if let Some(v) = surface
        .vertices
        .iter()
        .position(|p| !p.iter().all(|c| c.is_finite()))
    {
        return Err(format!(
            "vertex {v} has a coordinate that is not finite ({:?})",
            surface.vertices[v].as_slice()
        ));
    }
    let mut edges: HashMap<[usize; 2], usize> = HashMap::new();
    for t in &surface.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *edges.entry([a.min(b), a.max(b)]).or_default() += 1;
        }
    }
    match edges.iter().filter(|(_, &n)| n > 2).min() {
        Some((edge, n)) => Err(format!(
            "the edge {edge:?} is on {n} triangles: a cloth is a manifold surface (an edge on at most two)"
        )),
        None => Ok(()),
    }
}
