//! `isochor.Mesh` and `isochor.read_mesh`: a mesh's nodes, elements and named groups as numpy
//! arrays.

use crate::convert::{indices, points, rows};
use crate::errors::mesh_error;
use isochor_mesh::element::TetElement;
use isochor_mesh::io::{read_gmsh_with_groups, read_mesh_elements, read_tetgen_with_regions};
use isochor_mesh::{corner_numbering, ElementMesh, PhysicalGroup, PhysicalGroups, Vec3};
use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// One named group of a mesh.
#[derive(Clone)]
struct Group {
    key: String,
    dimension: usize,
    tag: i64,
    faces: Vec<i64>,
    tets: Vec<i64>,
}

/// A tet mesh: rest nodes, elements (4 or 10 nodes each, corners first, then the mid-edge
/// nodes in Gmsh's order), the region of each element and named groups. Every array
/// attribute is a new copy.
#[pyclass(module = "isochor", frozen)]
pub struct Mesh {
    nodes: Vec<Vec3>,
    elements: Vec<i64>,
    nodes_per_element: usize,
    /// `"tet4"` or `"tet10"`.
    #[pyo3(get)]
    kind: &'static str,
    /// Element corners (the first `num_vertices` nodes).
    #[pyo3(get)]
    num_vertices: usize,
    regions: Vec<i32>,
    groups: Vec<Group>,
}

impl Mesh {
    /// The mesh `mesh` with the region of each element and the groups `groups`.
    pub fn new(mesh: &ElementMesh, regions: Vec<i32>, groups: &PhysicalGroups) -> Mesh {
        Mesh {
            nodes: mesh.nodes().to_vec(),
            elements: indices(mesh.connectivity()),
            nodes_per_element: mesh.kind().num_nodes(),
            kind: mesh.kind().name(),
            num_vertices: mesh.num_vertices(),
            regions,
            groups: groups
                .iter()
                .map(|(key, g)| Group {
                    key: key.to_string(),
                    dimension: g.dimension,
                    tag: g.tag,
                    faces: g.faces.iter().flatten().map(|&i| i as i64).collect(),
                    tets: indices(&g.tets),
                })
                .collect(),
        }
    }
}

#[pymethods]
impl Mesh {
    /// Rest positions, `(nodes, 3)` float64.
    #[getter]
    fn nodes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        points(py, &self.nodes)
    }

    /// Node indices of each element, `(elements, 4 or 10)` int64.
    #[getter]
    fn elements<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        rows(py, self.elements.clone(), self.nodes_per_element)
    }

    /// Region of each element, `(elements,)` int32: 0 for the body's own material, `i` for
    /// the scene's `i`-th region (all 0 for a mesh read from a file).
    #[getter]
    fn region<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i32>> {
        PyArray1::from_vec(py, self.regions.clone())
    }

    /// Named groups: `{key: {"dimension": 2 or 3, "tag": int, "faces": (k, 3) int64 corner
    /// triangles, "tets": (k,) int64 element indices}}`, keyed by the group's name, else its
    /// tag (`"2:7"`, `"3:7"` when a surface and a volume group would share a key).
    #[getter]
    fn groups<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let all = PyDict::new(py);
        for g in &self.groups {
            let d = PyDict::new(py);
            d.set_item("dimension", g.dimension)?;
            d.set_item("tag", g.tag)?;
            d.set_item("faces", rows(py, g.faces.clone(), 3)?)?;
            d.set_item("tets", PyArray1::from_vec(py, g.tets.clone()))?;
            all.set_item(&g.key, d)?;
        }
        Ok(all)
    }

    /// Number of nodes.
    #[getter]
    fn num_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Number of elements.
    #[getter]
    fn num_elements(&self) -> usize {
        self.regions.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Mesh({} nodes, {} {} elements, {} groups)",
            self.nodes.len(),
            self.regions.len(),
            self.kind,
            self.groups.len()
        )
    }
}

/// Reads a mesh file by its extension: Gmsh `.msh` (2.2 or 4.1 ASCII, with its physical
/// groups), TetGen `.node`/`.ele` (its regions as volume groups) or `.vtu`; 4- or 10-node tets.
#[pyfunction]
pub fn read_mesh(py: Python<'_>, path: PathBuf) -> PyResult<Mesh> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (mesh, groups) = py
        .detach(|| match ext.as_deref() {
            Some("msh") => read_gmsh_with_groups(&path),
            Some("node" | "ele") => read_tetgen_with_regions(&path)
                .map(|(mesh, groups)| (ElementMesh::linear(mesh), groups)),
            _ => read_mesh_elements(&path).map(|m| (m, PhysicalGroups::default())),
        })
        .map_err(mesh_error)?;
    let regions = vec![0; mesh.num_elements()];
    Ok(Mesh::new(&mesh, regions, &groups))
}

/// A group of [`mesh_from_arrays`]: dimension, tag, name, triangles by input node (`(k, 3)`),
/// tets by element index.
type ArrayGroup<'py> = (
    usize,
    i64,
    Option<String>,
    PyReadonlyArray2<'py, i64>,
    PyReadonlyArray1<'py, i64>,
);

/// A mesh from arrays, as a file reader builds it: `nodes` `(n, 3)`, `elements` `(m, 4 or 10)`
/// (Gmsh's node order) and `groups`, their triangles listed by input node (renumbered as
/// the mesh numbers its corners). The package's `from_meshio` calls it.
#[pyfunction]
pub fn mesh_from_arrays(
    nodes: PyReadonlyArray2<'_, f64>,
    elements: PyReadonlyArray2<'_, i64>,
    groups: Vec<ArrayGroup<'_>>,
) -> PyResult<Mesh> {
    let bad = |m: String| crate::errors::MeshError::new_err(m);
    let index = |i: &i64| usize::try_from(*i).map_err(|_| bad(format!("negative index {i}")));
    let x = nodes.as_array();
    let positions: Vec<Vec3> = x
        .rows()
        .into_iter()
        .map(|r| Vec3::new(r[0], r[1], r[2]))
        .collect();
    let e = elements.as_array();
    let kind = match e.ncols() {
        4 => TetElement::Tet4,
        10 => TetElement::Tet10,
        n => return Err(bad(format!("elements: {n} nodes per element (4 or 10)"))),
    };
    let connectivity = e.iter().map(index).collect::<PyResult<Vec<_>>>()?;
    let vertex = corner_numbering(&connectivity, kind.num_nodes(), positions.len());
    let mut physical = Vec::new();
    for (dimension, tag, name, faces, tets) in groups {
        let faces = faces
            .as_array()
            .rows()
            .into_iter()
            .map(|f| {
                let corner = |i: &i64| {
                    vertex.get(index(i)?).copied().flatten().ok_or_else(|| {
                        bad(format!(
                            "group {tag}: triangle node {i} is no element's corner"
                        ))
                    })
                };
                Ok([corner(&f[0])?, corner(&f[1])?, corner(&f[2])?])
            })
            .collect::<PyResult<_>>()?;
        let tets = tets.as_array().iter().map(index).collect::<PyResult<_>>()?;
        physical.push(PhysicalGroup {
            dimension,
            tag,
            name,
            faces,
            tets,
        });
    }
    let mesh = ElementMesh::from_nodes(kind, positions, connectivity).map_err(mesh_error)?;
    let regions = vec![0; mesh.num_elements()];
    Ok(Mesh::new(&mesh, regions, &PhysicalGroups::new(physical)))
}
