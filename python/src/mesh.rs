//! `isochor.Mesh` and `isochor.read_mesh`: a mesh's nodes, elements and named groups as numpy
//! arrays.

use crate::convert::{indices, points, rows};
use crate::errors::mesh_error;
use isochor_mesh::io::{read_gmsh_with_groups, read_mesh_elements, read_tetgen_with_regions};
use isochor_mesh::{ElementMesh, PhysicalGroups, Vec3};
use numpy::{PyArray1, PyArray2};
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
