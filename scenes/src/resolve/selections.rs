//! Scene selections resolved on a mesh, once: a [`SelectionSpec`] becomes an
//! [`isochor_mesh::Region`] (the intersection of its primitives, padded by a tolerance), which
//! then selects nodes (vertices, and on a 10-node mesh the mid-edge nodes inside), boundary
//! faces (all three corners inside) and elements (corner centroid inside). A geometric
//! selection applies to any mesh of the same shape and element; a `physical` one takes a
//! named group of the mesh: a Gmsh physical group or TetGen region of the mesh file, or a
//! group its generator names (then cut by the region, if one is given). Every kind is
//! resolved for every selection; a kind a selection cannot give (a plane holds no tet's
//! centroid) is kept as the error its user meets.

use super::bodies::SceneBodies;
use super::mesh::SceneMesh;
use crate::error::SceneError;
use crate::format::SelectionSpec;
use isochor_mesh::element::Part;
use isochor_mesh::io::{PhysicalGroup, PhysicalGroups};
use isochor_mesh::{
    BoundarySurface, ElementMesh, FaceSelection, Region, TetMesh, Vec3, VertexSelection,
};
use std::collections::{BTreeMap, HashMap};

/// Every named selection of a scene as node, vertex, boundary-face and tet sets.
#[derive(Debug, Clone)]
pub struct Selections {
    sets: BTreeMap<String, Selected>,
}

/// What one selection selects of each kind (sorted, never empty), or why it selects nothing
/// of that kind.
#[derive(Debug, Clone)]
struct Selected {
    nodes: Result<Vec<usize>, String>,
    vertices: Result<Vec<usize>, String>,
    faces: Result<Vec<[usize; 3]>, String>,
    tets: Result<Vec<usize>, String>,
}

impl Selected {
    /// A selection that selects nothing of any kind, for `message`.
    fn failed(message: String) -> Self {
        Selected {
            nodes: Err(message.clone()),
            vertices: Err(message.clone()),
            faces: Err(message.clone()),
            tets: Err(message),
        }
    }

    /// What of this selection belongs to body `name` (lying in `part`).
    fn within(self, part: &Part, name: &str) -> Self {
        fn keep<T>(
            set: Result<Vec<T>, String>,
            belongs: impl Fn(&T) -> bool,
            what: &str,
            name: &str,
        ) -> Result<Vec<T>, String> {
            let mut set = set?;
            set.retain(belongs);
            if set.is_empty() {
                return Err(format!("selects no {what} of body '{name}'"));
            }
            Ok(set)
        }
        Selected {
            nodes: keep(self.nodes, |&n| part.has_node(n), "node", name),
            vertices: keep(self.vertices, |v| part.vertices.contains(v), "vertex", name),
            faces: keep(
                self.faces,
                |f| f.iter().all(|v| part.vertices.contains(v)),
                "boundary face",
                name,
            ),
            tets: keep(self.tets, |e| part.elements.contains(e), "tet", name),
        }
    }
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

/// The mesh and what every selection shares while being resolved.
struct Resolver<'a> {
    elements: &'a ElementMesh,
    mesh: &'a TetMesh,
    surface: BoundarySurface,
    /// The boundary nodes of a 10-node mesh (sorted), if a surface selection needs them.
    surface_nodes: Option<Vec<usize>>,
    default_tolerance: f64,
    groups: Option<&'a PhysicalGroups>,
    source: &'a str,
    bodies: &'a SceneBodies,
}

impl Selections {
    /// Resolves every selection of `specs` on the mesh and groups of a scene of one body
    /// (named `"body"`).
    pub fn new(
        mesh: &SceneMesh,
        specs: &BTreeMap<String, SelectionSpec>,
    ) -> Result<Self, SceneError> {
        Self::of_bodies(mesh, &SceneBodies::one(&mesh.mesh), specs)
    }

    /// Resolves every selection of `specs` on the scene's mesh and groups, a selection with
    /// `body` keeping what lies in that body.
    pub fn of_bodies(
        mesh: &SceneMesh,
        bodies: &SceneBodies,
        specs: &BTreeMap<String, SelectionSpec>,
    ) -> Result<Self, SceneError> {
        let elements = &mesh.mesh;
        let corners = elements.corners();
        let (lo, hi) = corners.bounding_box();
        let surface_like = specs.values().any(|s| s.surface || s.physical.is_some());
        let resolver = Resolver {
            elements,
            mesh: corners,
            surface: corners.boundary()?,
            surface_nodes: if surface_like && !elements.mid_edges().is_empty() {
                Some(elements.boundary()?.nodes())
            } else {
                None
            },
            default_tolerance: 1e-6 * (hi - lo).norm(),
            groups: mesh.groups.as_ref(),
            source: &mesh.source,
            bodies,
        };
        let sets = specs
            .iter()
            .map(|(name, spec)| (name.clone(), resolver.resolve(spec)))
            .collect();
        Ok(Selections { sets })
    }

    fn get(&self, name: &str) -> Result<&Selected, SceneError> {
        self.sets.get(name).ok_or_else(|| SceneError::Selection {
            name: name.to_string(),
            message: format!(
                "not defined (defined: {})",
                self.sets.keys().cloned().collect::<Vec<_>>().join(", ")
            ),
        })
    }

    /// The selected nodes (sorted, never empty): the selected vertices, then on a 10-node
    /// mesh the mid-edge nodes inside the region (on the boundary, for a surface selection)
    /// whose edge joins two selected vertices, so that a held face holds its whole quadratic
    /// faces.
    pub fn nodes(&self, name: &str) -> Result<&[usize], SceneError> {
        let set = &self.get(name)?.nodes;
        set.as_deref().map_err(|m| error(name, m))
    }

    /// The selected vertices (sorted, never empty).
    pub fn vertices(&self, name: &str) -> Result<&[usize], SceneError> {
        let set = &self.get(name)?.vertices;
        set.as_deref().map_err(|m| error(name, m))
    }

    /// The selected boundary faces, outward oriented (never empty).
    pub fn faces(&self, name: &str) -> Result<&[[usize; 3]], SceneError> {
        let set = &self.get(name)?.faces;
        set.as_deref().map_err(|m| error(name, m))
    }

    /// The tets whose rest centroid lies in the selection (never empty); of a physical
    /// selection, those of its volume group.
    pub fn tets(&self, name: &str) -> Result<&[usize], SceneError> {
        let set = &self.get(name)?.tets;
        set.as_deref().map_err(|m| error(name, m))
    }
}

/// The error of selection `name`.
fn error(name: &str, message: &str) -> SceneError {
    SceneError::Selection {
        name: name.to_string(),
        message: message.to_string(),
    }
}

/// The message of a selection that selects nothing of `what`.
fn empty(what: &str) -> String {
    format!(
        "selects no {what} of this mesh (check its coordinates against the mesh's bounding box)"
    )
}

impl Resolver<'_> {
    /// Every kind one selection selects.
    fn resolve(&self, spec: &SelectionSpec) -> Selected {
        let Some(body) = &spec.body else {
            return self.resolve_anywhere(spec);
        };
        match self.bodies.index(body) {
            Ok(b) => self
                .resolve_anywhere(spec)
                .within(&self.bodies.parts[b], body),
            Err(message) => Selected::failed(message),
        }
    }

    /// Every kind one selection selects on the whole mesh.
    fn resolve_anywhere(&self, spec: &SelectionSpec) -> Selected {
        let region = match region(spec, self.default_tolerance) {
            Ok(r) => r,
            Err(message) => return Selected::failed(message),
        };
        let physical = match self.physical(spec) {
            Ok(p) => p,
            Err(message) => return Selected::failed(message),
        };
        let vertices = self.vertices(spec, &region, physical.as_ref());
        let surface = spec.surface || physical.as_ref().is_some_and(|p| p.surface);
        Selected {
            nodes: vertices
                .as_ref()
                .map(|v| self.nodes(v, &region, surface))
                .map_err(Clone::clone),
            faces: self.faces(spec, &region, physical.as_ref()),
            tets: self.tets(&region, physical.as_ref()),
            vertices,
        }
    }

    /// What the selection's physical group selects, if it names one.
    fn physical(&self, spec: &SelectionSpec) -> Result<Option<Physical>, String> {
        let Some(key) = &spec.physical else {
            return Ok(None);
        };
        let Some(groups) = self.groups else {
            return Err(format!(
                "physical = \"{key}\" needs a mesh with named groups (a Gmsh .msh or TetGen .node/.ele file, or the generators spine, cushion, bubble, finger, torso and creature), but the scene's mesh is {}",
                self.source
            ));
        };
        let Some(group) = groups.get(key) else {
            let dimensions: Vec<String> = (0..=3)
                .filter(|d| groups.get(&format!("{d}:{key}")).is_some())
                .map(|d| d.to_string())
                .collect();
            if !dimensions.is_empty() {
                let keys: Vec<String> = dimensions
                    .iter()
                    .map(|d| format!("\"{d}:{key}\""))
                    .collect();
                return Err(format!(
                    "physical = \"{key}\" is ambiguous: {} has groups \"{key}\" of dimensions {}; name one as {}",
                    self.source,
                    dimensions.join(" and "),
                    keys.join(" or ")
                ));
            }
            let keys: Vec<&str> = groups.keys().collect();
            return Err(if keys.is_empty() {
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
            });
        };
        if group.dimension < 2 {
            let kind = if group.dimension == 0 {
                "points"
            } else {
                "curves"
            };
            return Err(format!(
                "physical group \"{key}\" is a group of {kind} (dimension {}): a selection takes a surface (2) or volume (3) group",
                group.dimension
            ));
        }
        self.group(group, spec.surface)
            .map(Some)
            .map_err(|m| format!("physical group \"{key}\" {m}"))
    }

    /// The vertices, boundary faces and tets of a physical group on this mesh.
    fn group(&self, group: &PhysicalGroup, surface: bool) -> Result<Physical, String> {
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

    /// The selected nodes of the selected `vertices` (see [`Selections::nodes`]).
    fn nodes(&self, vertices: &[usize], region: &Region, surface: bool) -> Vec<usize> {
        let nv = self.mesh.num_vertices();
        let mut selected = vec![false; nv];
        vertices.iter().for_each(|&v| selected[v] = true);
        let on_surface = self.surface_nodes.as_ref().filter(|_| surface);
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
                    && on_surface.is_none_or(|s| s.binary_search(&node).is_ok())
            })
            .map(|(node, _)| node);
        vertices.iter().copied().chain(mid).collect()
    }

    /// The selected vertices (see [`Selections::vertices`]).
    fn vertices(
        &self,
        spec: &SelectionSpec,
        region: &Region,
        physical: Option<&Physical>,
    ) -> Result<Vec<usize>, String> {
        let mut vertices = if let Some(physical) = physical {
            let x = self.mesh.positions();
            let mut v = physical.vertices.clone();
            v.retain(|&v| region.contains(&x[v]));
            v
        } else if spec.surface {
            VertexSelection::surface_from_region("", self.mesh, &self.surface, region).vertices
        } else {
            VertexSelection::from_region("", self.mesh, region).vertices
        };
        if let Some(explicit) = &spec.vertices {
            let n = self.mesh.num_vertices();
            if let Some(&bad) = explicit.iter().find(|&&v| v >= n) {
                return Err(format!(
                    "vertex {bad} is out of range (the mesh has {n} vertices)"
                ));
            }
            vertices.retain(|v| explicit.contains(v));
        }
        if vertices.is_empty() {
            return Err(empty("vertex"));
        }
        Ok(vertices)
    }

    /// The selected boundary faces (see [`Selections::faces`]).
    fn faces(
        &self,
        spec: &SelectionSpec,
        region: &Region,
        physical: Option<&Physical>,
    ) -> Result<Vec<[usize; 3]>, String> {
        let mut faces = if let Some(physical) = physical {
            if physical.off_boundary > 0 {
                return Err(format!(
                    "{} triangles of its physical group are not boundary faces of the mesh (loads act on the boundary)",
                    physical.off_boundary
                ));
            }
            let x = self.mesh.positions();
            let mut f = physical.faces.clone();
            f.retain(|f| f.iter().all(|&v| region.contains(&x[v])));
            f
        } else {
            FaceSelection::from_region("", self.mesh, &self.surface, region).faces
        };
        if let Some(explicit) = &spec.vertices {
            faces.retain(|f| f.iter().all(|v| explicit.contains(v)));
        }
        if faces.is_empty() {
            return Err(empty("boundary face"));
        }
        Ok(faces)
    }

    /// The selected tets (see [`Selections::tets`]).
    fn tets(&self, region: &Region, physical: Option<&Physical>) -> Result<Vec<usize>, String> {
        let candidates = match physical {
            Some(p) if p.surface && p.tets.is_empty() => return Err(
                "its physical group is a surface group: it selects no tets (name a volume group)"
                    .into(),
            ),
            Some(p) => p.tets.clone(),
            None => (0..self.mesh.num_tets()).collect(),
        };
        let tets: Vec<usize> = candidates
            .into_iter()
            .filter(|&e| region.contains(&self.mesh.centroid(e)))
            .collect();
        if tets.is_empty() {
            return Err(empty("tet"));
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
    use crate::format::{BoxSpec, PlaneSpec, RadialSpec};
    use isochor_mesh::generate::box_grid;

    /// `mesh` as a generated scene mesh without groups.
    fn generated(mesh: ElementMesh) -> SceneMesh {
        SceneMesh {
            mesh,
            groups: None,
            source: "a generated mesh".into(),
            notices: Vec::new(),
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
        let s = Selections::new(&generated(mesh), &specs()).unwrap();
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
        let mesh = generated(ElementMesh::quadratic(mesh));
        let s = Selections::new(&mesh, &specs()).unwrap();
        let left = s.nodes("left").unwrap();
        assert_eq!(left.len(), 25);
        assert!(left.iter().all(|&n| mesh.mesh.nodes()[n].x.abs() < 1e-12));
        assert_eq!(s.nodes("corner").unwrap().len(), 5);
    }
}
