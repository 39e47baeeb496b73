//! Scene selections resolved on a mesh: a [`SelectionSpec`] becomes an
//! [`isochor_mesh::Region`] (the intersection of its primitives, padded by a tolerance), which
//! then selects nodes (vertices, and on a 10-node mesh the mid-edge nodes inside), boundary
//! faces (all three corners inside) or elements (corner centroid inside). A geometric
//! selection applies to any mesh of the same shape and element; a `physical` one takes a
//! named group of the mesh: a Gmsh physical group or TetGen region of the mesh file, or a
//! group its generator names (then cut by the region, if one is given).

use crate::scene::{MeshSpec, SelectionSpec};
use crate::SceneError;
use isochor_mesh::generate;
use isochor_mesh::io::{
    read_gmsh_with_groups, read_tetgen_with_regions, PhysicalGroup, PhysicalGroups,
};
use isochor_mesh::{
    BoundarySurface, ElementMesh, FaceSelection, Region, TetMesh, Vec3, VertexSelection,
};
use std::collections::{BTreeMap, HashMap};

/// The selections of a scene on one mesh, with the boundary surface they share.
pub struct Selections<'a> {
    elements: &'a ElementMesh,
    mesh: &'a TetMesh,
    specs: &'a BTreeMap<String, SelectionSpec>,
    surface: BoundarySurface,
    default_tolerance: f64,
    /// The physical groups of a Gmsh mesh file, read if a selection names one.
    groups: Option<PhysicalGroups>,
    /// What the mesh is, for errors about physical groups.
    source: String,
}

/// What a physical group selects on the mesh: vertices (sorted), outward boundary faces,
/// tets, and whether it selects a surface.
struct Physical {
    vertices: Vec<usize>,
    faces: Vec<[usize; 3]>,
    tets: Vec<usize>,
    surface: bool,
    /// Triangles of a surface group that are not boundary faces (an internal surface).
    off_boundary: usize,
}

impl<'a> Selections<'a> {
    /// Prepares the selections of `specs` on `elements`, built from `source` (whose named
    /// groups are read from its file, or generated, if a selection names one).
    pub fn new(
        elements: &'a ElementMesh,
        source: &MeshSpec,
        specs: &'a BTreeMap<String, SelectionSpec>,
    ) -> Result<Self, SceneError> {
        let mesh = elements.corners();
        let (lo, hi) = mesh.bounding_box();
        let wanted = specs.values().any(|s| s.physical.is_some());
        let (groups, source) = match source {
            MeshSpec::File { path } => {
                let extension = path
                    .extension()
                    .map(|e| e.to_string_lossy().to_ascii_lowercase());
                let groups = match extension.as_deref() {
                    _ if !wanted => None,
                    Some("msh") => Some(read_gmsh_with_groups(path)?.1),
                    Some("node" | "ele") => Some(read_tetgen_with_regions(path)?.1),
                    _ => None,
                };
                (groups, format!("the mesh file {}", path.display()))
            }
            MeshSpec::Spine { .. }
            | MeshSpec::Cushion { .. }
            | MeshSpec::Bubble { .. }
            | MeshSpec::Finger { .. }
            | MeshSpec::Torso { .. }
            | MeshSpec::Creature { .. } => {
                let groups = if wanted {
                    generated_groups(source)?
                } else {
                    None
                };
                (groups, "a generated mesh with groups".to_string())
            }
            _ => (None, "a generated mesh".to_string()),
        };
        Ok(Selections {
            elements,
            mesh,
            specs,
            surface: mesh.boundary()?,
            default_tolerance: 1e-6 * (hi - lo).norm(),
            groups,
            source,
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

    /// What the selection's physical group selects, if it names one.
    fn physical(&self, name: &str) -> Result<Option<Physical>, SceneError> {
        let spec = self.spec(name)?;
        let Some(key) = &spec.physical else {
            return Ok(None);
        };
        let error = |message: String| SceneError::Selection {
            name: name.to_string(),
            message,
        };
        let Some(groups) = &self.groups else {
            return Err(error(format!(
                "physical = \"{key}\" needs a mesh with named groups (a Gmsh .msh or TetGen .node/.ele file, or the generators spine, cushion, bubble, finger, torso and creature), but the scene's mesh is {}",
                self.source
            )));
        };
        let Some(group) = groups.get(key) else {
            let keys: Vec<&str> = groups.keys().collect();
            return Err(error(if keys.is_empty() {
                format!(
                    "no physical group \"{key}\": {} has no physical surface or volume groups",
                    self.source
                )
            } else {
                format!(
                    "no physical group \"{key}\" in {} (groups: {})",
                    self.source,
                    keys.join(", ")
                )
            }));
        };
        self.resolve(group, spec.surface)
            .map(Some)
            .map_err(|m| error(format!("physical group \"{key}\" {m}")))
    }

    /// The vertices, boundary faces and tets of a physical group on this mesh.
    fn resolve(&self, group: &PhysicalGroup, surface: bool) -> Result<Physical, String> {
        let (nv, ne) = (self.mesh.num_vertices(), self.mesh.num_tets());
        if group.faces.iter().flatten().any(|&v| v >= nv) || group.tets.iter().any(|&e| e >= ne) {
            return Err("does not match the mesh (read the same file)".into());
        }
        let sorted = |f: &[usize; 3]| {
            let mut f = *f;
            f.sort_unstable();
            f
        };
        let triangles = self.surface.triangles();
        let boundary: HashMap<[usize; 3], usize> = triangles
            .iter()
            .enumerate()
            .map(|(i, f)| (sorted(f), i))
            .collect();
        let mut off_boundary = 0;
        let (faces, tets): (Vec<[usize; 3]>, Vec<usize>) = if group.dimension == 2 {
            let faces = group
                .faces
                .iter()
                .filter_map(|f| {
                    let face = boundary.get(&sorted(f)).map(|&i| triangles[i]);
                    off_boundary += usize::from(face.is_none());
                    face
                })
                .collect();
            (faces, Vec::new())
        } else {
            let mut inside = vec![false; ne];
            group.tets.iter().for_each(|&e| inside[e] = true);
            let faces = triangles
                .iter()
                .zip(self.surface.owner_tets())
                .filter(|&(_, &e)| inside[e])
                .map(|(f, _)| *f)
                .collect();
            (faces, group.tets.clone())
        };
        let mut vertices: Vec<usize> = if group.dimension == 2 {
            group.faces.iter().flatten().copied().collect()
        } else if surface {
            faces.iter().flatten().copied().collect()
        } else {
            tets.iter().flat_map(|&e| self.mesh.tets()[e]).collect()
        };
        vertices.sort_unstable();
        vertices.dedup();
        Ok(Physical {
            vertices,
            faces,
            tets,
            surface: surface || group.dimension == 2,
            off_boundary,
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
        let surface = self.spec(name)?.surface || self.physical(name)?.is_some_and(|p| p.surface);
        let on_surface = if surface && !self.elements.mid_edges().is_empty() {
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
        let mut vertices = if let Some(physical) = self.physical(name)? {
            let x = self.mesh.positions();
            let mut v = physical.vertices;
            v.retain(|&v| region.contains(&x[v]));
            v
        } else if spec.surface {
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
        let mut faces = if let Some(physical) = self.physical(name)? {
            if physical.off_boundary > 0 {
                return Err(SceneError::Selection {
                    name: name.to_string(),
                    message: format!(
                        "{} triangles of its physical group are not boundary faces of the mesh (loads act on the boundary)",
                        physical.off_boundary
                    ),
                });
            }
            let x = self.mesh.positions();
            let mut f = physical.faces;
            f.retain(|f| f.iter().all(|&v| region.contains(&x[v])));
            f
        } else {
            FaceSelection::from_region(name, self.mesh, &self.surface, &region).faces
        };
        if let Some(explicit) = &spec.vertices {
            faces.retain(|f| f.iter().all(|v| explicit.contains(v)));
        }
        if faces.is_empty() {
            return Err(Self::empty(name, "boundary face"));
        }
        Ok(faces)
    }

    /// The tets whose rest centroid lies in the selection (never empty); of a physical
    /// selection, those of its volume group.
    pub fn tets(&self, name: &str) -> Result<Vec<usize>, SceneError> {
        let region = self.region(name)?;
        let candidates = match self.physical(name)? {
            Some(p) if p.surface && p.tets.is_empty() => {
                return Err(SceneError::Selection {
                    name: name.to_string(),
                    message: "its physical group is a surface group: it selects no tets (name a volume group)".into(),
                })
            }
            Some(p) => p.tets,
            None => (0..self.mesh.num_tets()).collect(),
        };
        let tets: Vec<usize> = candidates
            .into_iter()
            .filter(|&e| region.contains(&self.mesh.centroid(e)))
            .collect();
        if tets.is_empty() {
            return Err(Self::empty(name, "tet"));
        }
        Ok(tets)
    }
}

/// The groups a generator names (its mesh is rebuilt: cheap beside a solve), `None` for a
/// generator that names none.
fn generated_groups(spec: &MeshSpec) -> Result<Option<PhysicalGroups>, SceneError> {
    Ok(Some(match spec {
        MeshSpec::Spine { res } => generate::spine_arm(*res)?.1,
        MeshSpec::Cushion { res } => generate::cushion(*res)?.1,
        MeshSpec::Bubble { res } => generate::bubble(*res)?.1,
        MeshSpec::Finger { res } => generate::finger(*res)?.1,
        MeshSpec::Torso { res } => generate::torso(*res)?.1,
        MeshSpec::Creature { res } => generate::creature(*res)?.1,
        _ => return Ok(None),
    }))
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

    fn generated() -> MeshSpec {
        MeshSpec::Explicit {
            positions: Vec::new(),
            tets: Vec::new(),
        }
    }

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
        let s = Selections::new(&mesh, &generated(), &specs).unwrap();
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
        let s = Selections::new(&mesh, &generated(), &specs).unwrap();
        let left = s.nodes("left").unwrap();
        assert_eq!(left.len(), 25);
        assert!(left.iter().all(|&n| mesh.nodes()[n].x.abs() < 1e-12));
        assert_eq!(s.nodes("corner").unwrap().len(), 5);
    }
}
