//! Named selections of vertices and of boundary faces, defined by geometric regions (boxes,
//! half-spaces, predicates), so that boundary conditions and loads apply to any mesh of the
//! same shape, generated or read from a file.

use crate::{BoundarySurface, MeshError, TetMesh, Vec3};
use std::fmt;
use std::sync::Arc;

/// A region of space: a point-membership test.
#[derive(Clone)]
pub struct Region {
    kind: RegionKind,
}

#[derive(Clone)]
enum RegionKind {
    Aabb { min: Vec3, max: Vec3 },
    HalfSpace { point: Vec3, normal: Vec3 },
    Predicate(Arc<dyn Fn(&Vec3) -> bool + Send + Sync>),
}

impl Region {
    /// The closed box `[min - tolerance, max + tolerance]` (per axis). Fails unless all values
    /// are finite, `min <= max` and `tolerance >= 0`.
    pub fn aabb(min: Vec3, max: Vec3, tolerance: f64) -> Result<Self, MeshError> {
        let finite = min.iter().chain(max.iter()).all(|c| c.is_finite());
        if !finite || (0..3).any(|a| min[a] > max[a]) {
            return Err(MeshError::parameter(
                "box",
                format!("min {:?}, max {:?}", min.as_slice(), max.as_slice()),
                "bounds must be finite with min <= max on every axis",
            ));
        }
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(MeshError::parameter(
                "tolerance",
                tolerance,
                "must be finite and >= 0",
            ));
        }
        let pad = Vec3::repeat(tolerance);
        Ok(Region {
            kind: RegionKind::Aabb {
                min: min - pad,
                max: max + pad,
            },
        })
    }

    /// The closed half-space `{x : (x - point) . normal >= 0}` on the side `normal` points to.
    /// Fails unless `point` is finite and `normal` finite and non-zero.
    pub fn half_space(point: Vec3, normal: Vec3) -> Result<Self, MeshError> {
        let norm = normal.norm();
        if !(point.iter().all(|c| c.is_finite()) && norm.is_finite() && norm > 0.0) {
            return Err(MeshError::parameter(
                "half_space",
                format!(
                    "point {:?}, normal {:?}",
                    point.as_slice(),
                    normal.as_slice()
                ),
                "point must be finite and normal finite and non-zero",
            ));
        }
        Ok(Region {
            kind: RegionKind::HalfSpace {
                point,
                normal: normal / norm,
            },
        })
    }

    /// Any membership test.
    pub fn predicate(f: impl Fn(&Vec3) -> bool + Send + Sync + 'static) -> Self {
        Region {
            kind: RegionKind::Predicate(Arc::new(f)),
        }
    }

    /// Whether `x` lies in the region.
    pub fn contains(&self, x: &Vec3) -> bool {
        match &self.kind {
            RegionKind::Aabb { min, max } => (0..3).all(|a| min[a] <= x[a] && x[a] <= max[a]),
            RegionKind::HalfSpace { point, normal } => (x - point).dot(normal) >= 0.0,
            RegionKind::Predicate(f) => f(x),
        }
    }
}

impl fmt::Debug for Region {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            RegionKind::Aabb { min, max } => f
                .debug_struct("Aabb")
                .field("min", &min.as_slice())
                .field("max", &max.as_slice())
                .finish(),
            RegionKind::HalfSpace { point, normal } => f
                .debug_struct("HalfSpace")
                .field("point", &point.as_slice())
                .field("normal", &normal.as_slice())
                .finish(),
            RegionKind::Predicate(_) => f.write_str("Predicate"),
        }
    }
}

/// A named, sorted, duplicate-free set of vertex indices.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VertexSelection {
    /// The selection's name.
    pub name: String,
    /// Its vertex indices, sorted, without duplicates.
    pub vertices: Vec<usize>,
}

impl VertexSelection {
    /// The vertices of `mesh` whose rest position lies in `region`.
    pub fn from_region(name: impl Into<String>, mesh: &TetMesh, region: &Region) -> Self {
        let vertices = (0..mesh.num_vertices())
            .filter(|&v| region.contains(&mesh.positions()[v]))
            .collect();
        VertexSelection {
            name: name.into(),
            vertices,
        }
    }

    /// The surface vertices of `mesh` whose rest position lies in `region`.
    pub fn surface_from_region(
        name: impl Into<String>,
        mesh: &TetMesh,
        surface: &BoundarySurface,
        region: &Region,
    ) -> Self {
        let vertices = surface
            .vertices()
            .iter()
            .copied()
            .filter(|&v| region.contains(&mesh.positions()[v]))
            .collect();
        VertexSelection {
            name: name.into(),
            vertices,
        }
    }

    /// Number of selected vertices.
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// Whether nothing was selected.
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }

    /// The selection itself, or [`MeshError::EmptySelection`] naming it if it is empty.
    pub fn non_empty(self) -> Result<Self, MeshError> {
        if self.is_empty() {
            return Err(MeshError::EmptySelection { name: self.name });
        }
        Ok(self)
    }
}

/// A named set of boundary triangles, outward oriented, in volume vertex indices.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaceSelection {
    /// The selection's name.
    pub name: String,
    /// Its boundary triangles, outward oriented.
    pub faces: Vec<[usize; 3]>,
}

impl FaceSelection {
    /// The boundary triangles of `surface` whose three vertices all lie in `region` (rest
    /// positions of `mesh`).
    pub fn from_region(
        name: impl Into<String>,
        mesh: &TetMesh,
        surface: &BoundarySurface,
        region: &Region,
    ) -> Self {
        let x = mesh.positions();
        Self::from_filter(name, surface, |t| t.iter().all(|&v| region.contains(&x[v])))
    }

    /// The boundary triangles of `surface` accepted by `keep`.
    pub fn from_filter(
        name: impl Into<String>,
        surface: &BoundarySurface,
        keep: impl Fn(&[usize; 3]) -> bool,
    ) -> Self {
        FaceSelection {
            name: name.into(),
            faces: surface.triangles().iter().copied().filter(keep).collect(),
        }
    }

    /// Sorted, duplicate-free vertices of the selected faces.
    pub fn vertices(&self) -> Vec<usize> {
        let mut v: Vec<usize> = self.faces.iter().flatten().copied().collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// Total area of the faces at positions `x`.
    pub fn area(&self, x: &[Vec3]) -> f64 {
        self.faces
            .iter()
            .map(|&[a, b, c]| 0.5 * (x[b] - x[a]).cross(&(x[c] - x[a])).norm())
            .sum()
    }

    /// Number of selected faces.
    pub fn len(&self) -> usize {
        self.faces.len()
    }

    /// Whether nothing was selected.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }

    /// The selection itself, or [`MeshError::EmptySelection`] naming it if it is empty.
    pub fn non_empty(self) -> Result<Self, MeshError> {
        if self.is_empty() {
            return Err(MeshError::EmptySelection { name: self.name });
        }
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::box_grid;

    fn unit_box() -> TetMesh {
        box_grid(Vec3::zeros(), Vec3::repeat(1.0), [4, 4, 4]).unwrap()
    }

    #[test]
    fn box_region_selects_a_face_with_tolerance() {
        let mesh = unit_box();
        let s = mesh.boundary().unwrap();
        let left = Region::aabb(Vec3::zeros(), Vec3::new(0.0, 1.0, 1.0), 1e-9).unwrap();
        let v = VertexSelection::from_region("left", &mesh, &left);
        assert_eq!(v.len(), 25);
        assert!(v.vertices.iter().all(|&i| mesh.positions()[i].x == 0.0));
        let f = FaceSelection::from_region("left", &mesh, &s, &left)
            .non_empty()
            .unwrap();
        assert_eq!(f.len(), 32);
        assert!((f.area(mesh.positions()) - 1.0).abs() < 1e-14);
        assert_eq!(f.vertices(), v.vertices);
        // The selected faces point along -x.
        assert!(f.faces.iter().all(|&[a, b, c]| {
            let x = mesh.positions();
            (x[b] - x[a]).cross(&(x[c] - x[a])).x < 0.0
        }));
    }

    #[test]
    fn half_space_and_predicate() {
        let mesh = unit_box();
        let s = mesh.boundary().unwrap();
        let top = Region::half_space(Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 0.0, 2.0)).unwrap();
        assert_eq!(VertexSelection::from_region("top", &mesh, &top).len(), 25);
        let above = Region::half_space(Vec3::new(0.0, 0.0, 0.5), Vec3::z()).unwrap();
        assert_eq!(
            VertexSelection::from_region("upper", &mesh, &above).len(),
            75
        );
        let on_axis = Region::predicate(|x| x.x == 0.5 && x.y == 0.5);
        let axis = VertexSelection::from_region("axis", &mesh, &on_axis);
        assert_eq!(axis.len(), 5);
        let axis_surface = VertexSelection::surface_from_region("axis", &mesh, &s, &on_axis);
        assert_eq!(axis_surface.len(), 2);
    }

    #[test]
    fn empty_and_invalid_regions_are_reported() {
        let mesh = unit_box();
        let far = Region::aabb(Vec3::repeat(5.0), Vec3::repeat(6.0), 0.0).unwrap();
        let v = VertexSelection::from_region("far", &mesh, &far);
        assert!(v.is_empty());
        let e = v.non_empty().unwrap_err();
        assert!(e.to_string().contains("\"far\""));
        assert!(Region::aabb(Vec3::repeat(1.0), Vec3::zeros(), 0.0).is_err());
        assert!(Region::aabb(Vec3::zeros(), Vec3::repeat(f64::NAN), 0.0).is_err());
        assert!(Region::aabb(Vec3::zeros(), Vec3::repeat(1.0), -1.0).is_err());
        assert!(Region::half_space(Vec3::zeros(), Vec3::zeros()).is_err());
    }
}
