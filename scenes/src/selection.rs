//! Scene selections resolved on a mesh: a [`SelectionSpec`] becomes an
//! [`isochor_mesh::Region`] (the intersection of its primitives, padded by a tolerance), which
//! then selects nodes (vertices, and on a 10-node mesh the mid-edge nodes inside), boundary
//! faces (all three corners inside) or elements (corner centroid inside). Everything is
//! geometric, so a selection applies to any mesh of the same shape and element.

use crate::scene::SelectionSpec;
use crate::SceneError;
use isochor_mesh::{
    BoundarySurface, ElementMesh, FaceSelection, Region, TetMesh, Vec3, VertexSelection,
};
use std::collections::BTreeMap;

/// The selections of a scene on one mesh, with the boundary surface they share.
pub struct Selections<'a> {
    elements: &'a ElementMesh,
    mesh: &'a TetMesh,
    specs: &'a BTreeMap<String, SelectionSpec>,
    surface: BoundarySurface,
    default_tolerance: f64,
}

impl<'a> Selections<'a> {
    /// Prepares the selections of `specs` on `elements`.
    pub fn new(
        elements: &'a ElementMesh,
        specs: &'a BTreeMap<String, SelectionSpec>,
    ) -> Result<Self, SceneError> {
        let mesh = elements.corners();
        let (lo, hi) = mesh.bounding_box();
        Ok(Selections {
            elements,
            mesh,
            specs,
            surface: mesh.boundary()?,
            default_tolerance: 1e-6 * (hi - lo).norm(),
        })
    }

    /// The boundary surface of the mesh.
    pub fn surface(&self) -> &BoundarySurface {
        &self.surface
    }

    fn spec(&self, name: &str) -> Result<&'a SelectionSpec, SceneError> {
        self.specs.get(name).ok_or_else(|| SceneError::Selection {
            name: name.to_string(),
            message: format!(
                "not defined (defined: {})",
                self.specs.keys().cloned().collect::<Vec<_>>().join(", ")
            ),
        })
    }

    fn region(&self, name: &str) -> Result<Region, SceneError> {
        region(self.spec(name)?, self.default_tolerance).map_err(|message| SceneError::Selection {
            name: name.to_string(),
            message,
        })
    }

    fn empty(name: &str, what: &str) -> SceneError {
        SceneError::Selection {
            name: name.to_string(),
            message: format!("selects no {what} of this mesh (check its coordinates against the mesh's bounding box)"),
        }
    }

    /// The selected nodes (sorted, never empty): the selected vertices, then on a 10-node
    /// mesh the mid-edge nodes inside the region (on the boundary, for a surface selection)
    /// whose edge joins two selected vertices, so that a held face holds its whole quadratic
    /// faces.
    pub fn nodes(&self, name: &str) -> Result<Vec<usize>, SceneError> {
        let vertices = self.vertices(name)?;
        let region = self.region(name)?;
        let nv = self.mesh.num_vertices();
        let mut selected = vec![false; nv];
        vertices.iter().for_each(|&v| selected[v] = true);
        let on_surface = if self.spec(name)?.surface && !self.elements.mid_edges().is_empty() {
            Some(self.elements.boundary()?.nodes())
        } else {
            None
        };
        let x = self.elements.nodes();
        let mid = self
            .elements
            .mid_edges()
            .iter()
            .enumerate()
            .map(|(i, edge)| (nv + i, edge))
            .filter(|&(node, &[a, b])| {
                selected[a]
                    && selected[b]
                    && region.contains(&x[node])
                    && on_surface
                        .as_ref()
                        .is_none_or(|s| s.binary_search(&node).is_ok())
            })
            .map(|(node, _)| node);
        Ok(vertices.iter().copied().chain(mid).collect())
    }

    /// The selected vertices (sorted, never empty).
    pub fn vertices(&self, name: &str) -> Result<Vec<usize>, SceneError> {
        let spec = self.spec(name)?;
        let region = self.region(name)?;
        let mut vertices = if spec.surface {
            VertexSelection::surface_from_region(name, self.mesh, &self.surface, &region).vertices
        } else {
            VertexSelection::from_region(name, self.mesh, &region).vertices
        };
        if let Some(explicit) = &spec.vertices {
            let n = self.mesh.num_vertices();
            if let Some(&bad) = explicit.iter().find(|&&v| v >= n) {
                return Err(SceneError::Selection {
                    name: name.to_string(),
                    message: format!("vertex {bad} is out of range (the mesh has {n} vertices)"),
                });
            }
            vertices.retain(|v| explicit.contains(v));
        }
        if vertices.is_empty() {
            return Err(Self::empty(name, "vertex"));
        }
        Ok(vertices)
    }

    /// The selected boundary faces, outward oriented (never empty).
    pub fn faces(&self, name: &str) -> Result<Vec<[usize; 3]>, SceneError> {
        let spec = self.spec(name)?;
        let region = self.region(name)?;
        let mut faces = FaceSelection::from_region(name, self.mesh, &self.surface, &region).faces;
        if let Some(explicit) = &spec.vertices {
            faces.retain(|f| f.iter().all(|v| explicit.contains(v)));
        }
        if faces.is_empty() {
            return Err(Self::empty(name, "boundary face"));
        }
        Ok(faces)
    }

    /// The tets whose rest centroid lies in the selection (never empty).
    pub fn tets(&self, name: &str) -> Result<Vec<usize>, SceneError> {
        let region = self.region(name)?;
        let tets: Vec<usize> = (0..self.mesh.num_tets())
            .filter(|&e| region.contains(&self.mesh.centroid(e)))
            .collect();
        if tets.is_empty() {
            return Err(Self::empty(name, "tet"));
        }
        Ok(tets)
    }
}

/// The region of a selection: the intersection of its primitives.
fn region(spec: &SelectionSpec, default_tolerance: f64) -> Result<Region, String> {
    let tol = spec.tolerance.unwrap_or(default_tolerance);
    let v = |a: [f64; 3]| Vec3::new(a[0], a[1], a[2]);
    let unit = |a: [f64; 3], what: &str| {
        let n = v(a);
        let norm = n.norm();
        if norm.is_finite() && norm > 0.0 {
            Ok(n / norm)
        } else {
            Err(format!(
                "{what} must be a finite non-zero vector, not {a:?}"
            ))
        }
    };
    let mut parts: Vec<Region> = Vec::new();
    if let Some(b) = &spec.aabb {
        parts.push(Region::aabb(v(b.min), v(b.max), tol).map_err(|e| e.to_string())?);
    }
    if let Some(p) = &spec.plane {
        let (point, normal) = (v(p.point), unit(p.normal, "plane.normal")?);
        parts.push(Region::predicate(move |x| {
            ((x - point).dot(&normal)).abs() <= tol
        }));
    }
    if let Some(p) = &spec.half_space {
        let (point, normal) = (v(p.point), unit(p.normal, "half_space.normal")?);
        parts.push(Region::predicate(move |x| (x - point).dot(&normal) >= -tol));
    }
    if let Some(r) = &spec.radial {
        let (center, axis) = (v(r.center), unit(r.axis, "radial.axis")?);
        let (min, max) = (r.min, r.max);
        if min.is_nan() || max.is_nan() || min > max {
            return Err(format!("radial needs min <= max, not [{min}, {max}]"));
        }
        parts.push(Region::predicate(move |x| {
            let d = x - center;
            let r = (d - d.dot(&axis) * axis).norm();
            r >= min - tol && r <= max + tol
        }));
    }
    if let Some(s) = &spec.sphere {
        let (center, radius) = (v(s.center), s.radius);
        if !(radius.is_finite() && radius >= 0.0) {
            return Err(format!(
                "sphere.radius must be finite and >= 0, not {radius}"
            ));
        }
        parts.push(Region::predicate(move |x| {
            (x - center).norm() <= radius + tol
        }));
    }
    Ok(Region::predicate(move |x| {
        parts.iter().all(|r| r.contains(x))
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{BoxSpec, PlaneSpec, RadialSpec};
    use isochor_mesh::generate::box_grid;

    fn specs() -> BTreeMap<String, SelectionSpec> {
        let mut m = BTreeMap::new();
        m.insert(
            "left".to_string(),
            SelectionSpec {
                plane: Some(PlaneSpec {
                    point: [0.0; 3],
                    normal: [1.0, 0.0, 0.0],
                }),
                ..Default::default()
            },
        );
        m.insert(
            "corner".to_string(),
            SelectionSpec {
                aabb: Some(BoxSpec {
                    min: [0.0; 3],
                    max: [0.5, 0.5, 1.0],
                }),
                radial: Some(RadialSpec {
                    center: [0.0; 3],
                    axis: [0.0, 0.0, 1.0],
                    min: 0.0,
                    max: 0.1,
                }),
                ..Default::default()
            },
        );
        m.insert(
            "nowhere".to_string(),
            SelectionSpec {
                aabb: Some(BoxSpec {
                    min: [5.0; 3],
                    max: [6.0; 3],
                }),
                ..Default::default()
            },
        );
        m
    }

    #[test]
    fn selections_pick_vertices_faces_and_tets() {
        let mesh =
            ElementMesh::linear(box_grid(Vec3::zeros(), Vec3::repeat(1.0), [2, 2, 2]).unwrap());
        let specs = specs();
        let s = Selections::new(&mesh, &specs).unwrap();
        assert_eq!(s.vertices("left").unwrap().len(), 9);
        assert_eq!(s.nodes("left").unwrap(), s.vertices("left").unwrap());
        assert_eq!(s.faces("left").unwrap().len(), 8);
        // The corner column: the vertices on the z axis.
        assert_eq!(s.vertices("corner").unwrap().len(), 3);
        assert!(s.tets("left").is_err(), "no centroid lies on the plane");
        let e = s.vertices("nowhere").unwrap_err().to_string();
        assert!(e.contains("nowhere") && e.contains("no vertex"), "{e}");
        assert!(s
            .vertices("undefined")
            .unwrap_err()
            .to_string()
            .contains("defined: corner, left, nowhere"));
    }

    /// On 10-node tets a plane selection holds every node of its quadratic faces: the 9
    /// vertices of the x = 0 face of a 2x2x2 box, the 12 mid-edge nodes of its grid edges
    /// and the 4 of its face diagonals; the corner column gets the 2 mid-edge nodes between
    /// its 3 vertices.
    #[test]
    fn selections_on_quadratic_tets_include_the_mid_edge_nodes() {
        let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [2, 2, 2]).unwrap();
        let mesh = ElementMesh::quadratic(mesh);
        let specs = specs();
        let s = Selections::new(&mesh, &specs).unwrap();
        let left = s.nodes("left").unwrap();
        assert_eq!(left.len(), 25);
        assert!(left.iter().all(|&n| mesh.nodes()[n].x.abs() < 1e-12));
        assert_eq!(s.nodes("corner").unwrap().len(), 5);
    }
}
