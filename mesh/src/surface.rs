//! The boundary surface of a tet mesh, or of any set of its tets (e.g. a zone): the faces that
//! belong to exactly one tet of the set, oriented outward.
//!
//! A zone volume can be computed from its boundary faces alone by the divergence theorem
//! (Sheen et al. 2021, remark after eq. 7), which is what [`BoundarySurface::enclosed_volume`]
//! does.

use crate::{MeshError, TetMesh, Vec3};

/// The four faces of a positively oriented tet `[x0, x1, x2, x3]`; face `f` is opposite local
/// vertex `f`, and its right-hand normal points out of the tet.
pub const TET_FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// Outward-oriented boundary triangles of a set of tets, with their owning tets, the sorted
/// set of surface vertices and the rest area of every triangle.
///
/// Triangles use volume vertex indices and are ordered by their sorted vertex triple, so the
/// surface of a given mesh is always the same list.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundarySurface {
    triangles: Vec<[usize; 3]>,
    owners: Vec<usize>,
    owner_faces: Vec<usize>,
    vertices: Vec<usize>,
    rest_areas: Vec<f64>,
}

impl BoundarySurface {
    /// The boundary of the whole mesh: every face that appears in exactly one tet.
    ///
    /// Fails with [`MeshError::NonManifoldFace`] if a face is shared by more than two tets.
    pub fn new(mesh: &TetMesh) -> Result<Self, MeshError> {
        Self::build(mesh, 0..mesh.num_tets())
    }

    /// The boundary of the tets `tets` (any order, duplicates ignored): the faces of these
    /// tets that are not shared by two of them, oriented out of the set.
    pub fn of_tets(mesh: &TetMesh, tets: &[usize]) -> Result<Self, MeshError> {
        let mut set = tets.to_vec();
        set.sort_unstable();
        set.dedup();
        if let Some(&tet) = set.last().filter(|&&t| t >= mesh.num_tets()) {
            return Err(MeshError::TetOutOfRange {
                tet,
                tets: mesh.num_tets(),
            });
        }
        Self::build(mesh, set.into_iter())
    }

    fn build(mesh: &TetMesh, tets: impl Iterator<Item = usize>) -> Result<Self, MeshError> {
        // (sorted vertex triple, owning tet, oriented triangle, local face) for every face of
        // every tet.
        let mut faces: Vec<([usize; 3], usize, [usize; 3], usize)> = Vec::new();
        for e in tets {
            let t = mesh.tets()[e];
            for (f, local) in TET_FACES.into_iter().enumerate() {
                let tri = local.map(|a| t[a]);
                let mut key = tri;
                key.sort_unstable();
                faces.push((key, e, tri, f));
            }
        }
        faces.sort_unstable_by_key(|f| (f.0, f.1));
        let mut triangles = Vec::new();
        let mut owners = Vec::new();
        let mut owner_faces = Vec::new();
        for run in faces.chunk_by(|a, b| a.0 == b.0) {
            match run.len() {
                1 => {
                    triangles.push(run[0].2);
                    owners.push(run[0].1);
                    owner_faces.push(run[0].3);
                }
                2 => {}
                count => {
                    return Err(MeshError::NonManifoldFace {
                        face: run[0].0,
                        count,
                    })
                }
            }
        }
        let mut vertices: Vec<usize> = triangles.iter().flatten().copied().collect();
        vertices.sort_unstable();
        vertices.dedup();
        let x = mesh.positions();
        let rest_areas = triangles
            .iter()
            .map(|&[a, b, c]| 0.5 * (x[b] - x[a]).cross(&(x[c] - x[a])).norm())
            .collect();
        Ok(BoundarySurface {
            triangles,
            owners,
            owner_faces,
            vertices,
            rest_areas,
        })
    }

    /// Outward triangles (right-hand normal points out of the tets) in volume vertex indices.
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// The tet that owns each triangle.
    pub fn owner_tets(&self) -> &[usize] {
        &self.owners
    }

    /// The local face (`0..4`, the face of [`TET_FACES`] opposite that corner) of each
    /// triangle in its owner tet: triangle `i` is `TET_FACES[owner_faces()[i]]` of tet
    /// `owner_tets()[i]`.
    pub fn owner_faces(&self) -> &[usize] {
        &self.owner_faces
    }

    /// Sorted, duplicate-free indices of the vertices on the surface.
    pub fn vertices(&self) -> &[usize] {
        &self.vertices
    }

    /// Rest area of every triangle.
    pub fn rest_areas(&self) -> &[f64] {
        &self.rest_areas
    }

    /// Total rest area.
    pub fn rest_area(&self) -> f64 {
        self.rest_areas.iter().sum()
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether the surface has no triangle.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Area-weighted outward normal `(x1 - x0) x (x2 - x0) / 2` of triangle `f` at positions `x`.
    pub fn area_normal(&self, f: usize, x: &[Vec3]) -> Vec3 {
        let [a, b, c] = self.triangles[f];
        0.5 * (x[b] - x[a]).cross(&(x[c] - x[a]))
    }

    /// Volume enclosed by the surface at positions `x`, by the divergence theorem:
    /// `sum_f x0 . (x1 x x2) / 6`. Equals the summed signed volume of the tets it bounds.
    pub fn enclosed_volume(&self, x: &[Vec3]) -> f64 {
        self.triangles
            .iter()
            .map(|&[a, b, c]| x[a].dot(&x[b].cross(&x[c])))
            .sum::<f64>()
            / 6.0
    }

    /// Checks that the surface is closed, manifold and consistently oriented; see
    /// [`check_closed_manifold`].
    pub fn check_closed(&self) -> Result<(), MeshError> {
        check_closed_manifold(&self.triangles)
    }
}

impl TetMesh {
    /// The boundary surface of the mesh; see [`BoundarySurface::new`].
    pub fn boundary(&self) -> Result<BoundarySurface, MeshError> {
        BoundarySurface::new(self)
    }
}

/// Checks that every edge of `triangles` is shared by exactly two triangles that traverse it
/// in opposite directions. Reports the first bad edge (smallest vertex pair) as
/// [`MeshError::OpenBoundary`], [`MeshError::NonManifoldEdge`] or
/// [`MeshError::InconsistentOrientation`]. Two solids touching at a single vertex are not
/// detected (no edge is affected).
pub fn check_closed_manifold(triangles: &[[usize; 3]]) -> Result<(), MeshError> {
    for run in edge_runs(triangles).chunk_by(|a, b| a.edge == b.edge) {
        if run.len() == 1 {
            return Err(MeshError::OpenBoundary { edge: run[0].edge });
        }
        manifold_pair(run)?;
    }
    Ok(())
}

/// The hinges of a consistently oriented manifold triangle surface, open or closed: for every
/// edge shared by two triangles `(a, b, c)` and `(b, a, d)`, the four vertices `[a, b, c, d]`
/// (the shared edge first, then the vertex opposite it in each triangle), ordered by edge.
/// Boundary edges (one triangle) have no hinge. Errors as [`check_closed_manifold`] on an
/// edge shared by more than two triangles or traversed twice in one direction.
pub fn hinges(triangles: &[[usize; 3]]) -> Result<Vec<[usize; 4]>, MeshError> {
    let mut hinges = Vec::new();
    for run in edge_runs(triangles).chunk_by(|a, b| a.edge == b.edge) {
        if run.len() > 1 {
            manifold_pair(run)?;
            let (first, second) = (&run[0], &run[1]);
            hinges.push([first.from, first.to, first.opposite, second.opposite]);
        }
    }
    Ok(hinges)
}

/// One triangle's traversal of one of its edges.
struct EdgeUse {
    /// The edge's vertices, sorted.
    edge: [usize; 2],
    /// The edge's vertices in the triangle's order.
    from: usize,
    to: usize,
    /// The triangle's third vertex.
    opposite: usize,
}

/// Every edge traversal of `triangles`, sorted by edge (the traversal from the smaller vertex
/// first).
fn edge_runs(triangles: &[[usize; 3]]) -> Vec<EdgeUse> {
    let mut uses: Vec<EdgeUse> = triangles
        .iter()
        .flat_map(|t| {
            (0..3).map(move |i| EdgeUse {
                edge: [t[i].min(t[(i + 1) % 3]), t[i].max(t[(i + 1) % 3])],
                from: t[i],
                to: t[(i + 1) % 3],
                opposite: t[(i + 2) % 3],
            })
        })
        .collect();
    uses.sort_unstable_by_key(|u| (u.edge, u.from != u.edge[0], u.opposite));
    uses
}

/// A run of two or more traversals of one edge: an error unless exactly two, in opposite
/// directions.
fn manifold_pair(run: &[EdgeUse]) -> Result<(), MeshError> {
    let edge = run[0].edge;
    match run {
        [a, b] if a.from == b.from => Err(MeshError::InconsistentOrientation { edge }),
        [_, _] => Ok(()),
        _ => Err(MeshError::NonManifoldEdge {
            edge,
            count: run.len(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::box_grid;

    fn unit_tet() -> TetMesh {
        let x = vec![Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()];
        TetMesh::new(x, vec![[0, 1, 2, 3]]).unwrap()
    }

    #[test]
    fn tet_faces_point_outward() {
        let mesh = unit_tet();
        let s = mesh.boundary().unwrap();
        assert_eq!(s.len(), 4);
        let x = mesh.positions();
        let centroid = mesh.centroid(0);
        for f in 0..4 {
            let [a, b, c] = s.triangles()[f];
            let face_center = (x[a] + x[b] + x[c]) / 3.0;
            assert!(s.area_normal(f, x).dot(&(face_center - centroid)) > 0.0);
        }
        assert!((s.enclosed_volume(x) - 1.0 / 6.0).abs() < 1e-15);
        assert_eq!(s.vertices(), &[0, 1, 2, 3]);
        s.check_closed().unwrap();
    }

    #[test]
    fn box_surface_is_closed_outward_and_exact() {
        let (lo, hi) = (Vec3::new(-1.0, 0.0, 0.5), Vec3::new(2.0, 1.0, 2.5));
        let mesh = box_grid(lo, hi, [3, 2, 4]).unwrap();
        let s = mesh.boundary().unwrap();
        s.check_closed().unwrap();
        let x = mesh.positions();
        // 2 triangles per boundary quad.
        assert_eq!(s.len(), 2 * 2 * (3 * 2 + 2 * 4 + 3 * 4));
        let (dx, dy, dz) = (3.0, 1.0, 2.0);
        let area = 2.0 * (dx * dy + dy * dz + dx * dz);
        assert!((s.rest_area() - area).abs() < 1e-13);
        // Each normal is along one axis and points away from the box.
        let mut sum = Vec3::zeros();
        for f in 0..s.len() {
            let n = s.area_normal(f, x);
            sum += n;
            let [a, b, c] = s.triangles()[f];
            let face_center = (x[a] + x[b] + x[c]) / 3.0;
            let axis = n.iamax();
            let outward = if face_center[axis] > 0.5 * (lo[axis] + hi[axis]) {
                1.0
            } else {
                -1.0
            };
            assert!(n[axis] * outward > 0.0, "triangle {f} points inward");
            assert!((n.norm() - n[axis].abs()).abs() < 1e-15);
        }
        assert!(sum.norm() < 1e-13);
        assert!((s.enclosed_volume(x) - mesh.rest_volume()).abs() < 1e-13);
        // All 4 x 3 x 5 grid vertices but the (4-2) x (3-2) x (5-2) interior ones.
        let surface_vertices = 4 * 3 * 5 - 2 * 3;
        assert_eq!(s.vertices().len(), surface_vertices);
        for (f, &e) in s.owner_tets().iter().enumerate() {
            let t = mesh.tets()[e];
            assert!(s.triangles()[f].iter().all(|v| t.contains(v)));
        }
    }

    #[test]
    fn tet_set_boundary_bounds_its_volume() {
        let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [3, 3, 3]).unwrap();
        let x = mesh.positions();
        // A slab is a closed manifold; a scattered set touches itself along edges but the
        // divergence theorem still holds.
        let slab: Vec<usize> = (0..mesh.num_tets())
            .filter(|&e| mesh.centroid(e).z < 1.0 / 3.0)
            .collect();
        let s = BoundarySurface::of_tets(&mesh, &slab).unwrap();
        s.check_closed().unwrap();
        assert_eq!(slab.len(), mesh.num_tets() / 3);
        assert!((s.enclosed_volume(x) - 1.0 / 3.0).abs() < 1e-14);
        assert!((s.rest_area() - (2.0 + 4.0 / 3.0)).abs() < 1e-14);
        let set: Vec<usize> = (0..mesh.num_tets()).filter(|e| e % 3 != 0).collect();
        let s = BoundarySurface::of_tets(&mesh, &set).unwrap();
        assert!(matches!(
            s.check_closed(),
            Err(MeshError::NonManifoldEdge { .. })
        ));
        let volume: f64 = set.iter().map(|&e| mesh.rest_volumes()[e]).sum();
        assert!((s.enclosed_volume(x) - volume).abs() < 1e-14);
        assert!(s.owner_tets().iter().all(|e| e % 3 != 0));
        let e = BoundarySurface::of_tets(&mesh, &[0, 999]).unwrap_err();
        assert!(matches!(e, MeshError::TetOutOfRange { tet: 999, .. }));
    }

    #[test]
    fn defects_name_the_face_or_edge() {
        // Three tets on one face.
        let x = vec![
            Vec3::zeros(),
            Vec3::x(),
            Vec3::y(),
            Vec3::z(),
            -Vec3::z(),
            Vec3::new(0.1, 0.1, 1.0),
        ];
        let mesh = TetMesh::new(x, vec![[0, 1, 2, 3], [0, 1, 2, 4], [0, 1, 2, 5]]).unwrap();
        let e = mesh.boundary().unwrap_err();
        assert!(matches!(
            e,
            MeshError::NonManifoldFace {
                face: [0, 1, 2],
                count: 3
            }
        ));
        // Two tets sharing only the edge 0-1.
        let x = vec![
            Vec3::zeros(),
            Vec3::x(),
            Vec3::y(),
            Vec3::z(),
            -Vec3::y(),
            -Vec3::z(),
        ];
        let mesh = TetMesh::new(x, vec![[0, 1, 2, 3], [0, 1, 4, 5]]).unwrap();
        let e = mesh.boundary().unwrap().check_closed().unwrap_err();
        assert!(matches!(
            e,
            MeshError::NonManifoldEdge {
                edge: [0, 1],
                count: 4
            }
        ));
        assert!(e.to_string().contains("[0, 1]"));
        let e = check_closed_manifold(&[[0, 1, 2]]).unwrap_err();
        assert!(matches!(e, MeshError::OpenBoundary { edge: [0, 1] }));
        let e = check_closed_manifold(&[[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]).unwrap_err();
        assert!(matches!(
            e,
            MeshError::InconsistentOrientation { edge: [0, 1] }
        ));
    }

    #[test]
    fn hinges_of_an_open_strip_pair_each_shared_edge_with_its_opposite_vertices() {
        // A square split along its diagonal 0-2, plus a triangle on the edge 1-2.
        let triangles = [[0, 1, 2], [0, 2, 3], [2, 1, 4]];
        let h = hinges(&triangles).unwrap();
        assert_eq!(h, vec![[0, 2, 3, 1], [1, 2, 0, 4]]);
        let folded = [[0, 1, 2], [0, 1, 3]];
        assert!(matches!(
            hinges(&folded),
            Err(MeshError::InconsistentOrientation { edge: [0, 1] })
        ));
        let fin = [[0, 1, 2], [1, 0, 3], [0, 1, 4]];
        assert!(matches!(
            hinges(&fin),
            Err(MeshError::NonManifoldEdge {
                edge: [0, 1],
                count: 3
            })
        ));
    }
}
