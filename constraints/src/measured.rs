//! What every constraint set shares: the elements with their rest geometry at the points of
//! one quadrature rule and the measure `Phi(J)` integrated over them, the DOF layout of element
//! blocks, argument checks, and the parallel fill of Jacobian rows and geometric stiffness
//! blocks into caller-owned buffers.
//!
//! Every constraint row is a sum of element integrals `integral_e c(xi) Phi(J) dV`, evaluated
//! as `sum_q W_q c(xi_q) Phi(J_q)` with `W_q = w_q det(dX/dxi)(xi_q)`, where the row's shape
//! `c` is one of [`RowShape`]. `Phi(det F)` is a density like an energy's, so its derivatives
//! come from the quadrature kernel of `isochor-energies` ([`kernel::evaluate`]): the
//! constraints have no chain rule of their own.

use crate::{ConstraintError, Measure, RowShape};
use isochor_energies::kernel::{self, RestPoints};
use isochor_mesh::element::{deformation_gradient, RestGeometry, TetElement, TetQuadrature};
use isochor_mesh::{ElementMesh, Vec3};
use rayon::prelude::*;

/// Smallest number of elements a rayon task handles (per-element work of a 4-node tet is well
/// under a microsecond, so finer splitting costs more than it gains).
const ELEMENTS_PER_TASK: usize = 256;

/// The most points of any [`TetQuadrature`] rule.
const MAX_POINTS: usize = 15;

/// The elements of a mesh with their rest geometry at the points of one rule, and the
/// measure `Phi(J)` every constraint row is assembled from.
#[derive(Debug, Clone)]
pub(crate) struct MeasuredElements {
    measure: Measure,
    kind: TetElement,
    connectivity: Vec<usize>,
    num_nodes: usize,
    num_vertices: usize,
    geometry: RestGeometry,
    /// `L_j(xi_q)`, the corner (barycentric) shape functions at every point of the rule.
    corner_values: Vec<[f64; 4]>,
    /// `integral_e L_i L_j dV`, exact, for the compliance.
    corner_products: Vec<[[f64; 4]; 4]>,
}

impl MeasuredElements {
    /// The elements of `mesh` at the points of `rule`.
    pub(crate) fn new(
        mesh: &ElementMesh,
        rule: TetQuadrature,
        measure: Measure,
    ) -> Result<Self, ConstraintError> {
        let geometry = rest_geometry(mesh, rule)?;
        let corner_values = rule.points().iter().map(corner_shapes).collect();
        // L_i L_j det(dX/dxi) has degree 2 + 3 (p - 1) on elements of order p: the degree-2
        // rule is exact on 4-node tets, the degree-5 rule on 10-node tets.
        let exact_rule = match mesh.kind() {
            TetElement::Tet4 => TetQuadrature::Degree2,
            TetElement::Tet10 => TetQuadrature::Degree5,
        };
        let other = (exact_rule != rule)
            .then(|| rest_geometry(mesh, exact_rule))
            .transpose()?;
        let exact = other.as_ref().unwrap_or(&geometry);
        let exact_shapes: Vec<[f64; 4]> = exact_rule.points().iter().map(corner_shapes).collect();
        let corner_products = (0..mesh.num_elements())
            .map(|e| {
                let weights = exact.element_weights(e);
                // Exactly symmetric: entry (i, j) sums the products in the order (min, max).
                std::array::from_fn(|i| {
                    std::array::from_fn(|j| {
                        let (a, b) = (i.min(j), i.max(j));
                        let terms = exact_shapes.iter().zip(weights);
                        terms.map(|(l, w)| w * l[a] * l[b]).sum()
                    })
                })
            })
            .collect();
        Ok(MeasuredElements {
            measure,
            kind: mesh.kind(),
            connectivity: mesh.connectivity().to_vec(),
            num_nodes: mesh.num_nodes(),
            num_vertices: mesh.num_vertices(),
            geometry,
            corner_values,
            corner_products,
        })
    }

    pub(crate) fn measure(&self) -> Measure {
        self.measure
    }

    /// Number of elements.
    pub(crate) fn len(&self) -> usize {
        self.corner_products.len()
    }

    /// Number of corner vertices (nodes `0..num_vertices`).
    pub(crate) fn num_vertices(&self) -> usize {
        self.num_vertices
    }

    /// The nodes of element `e`.
    pub(crate) fn nodes(&self, e: usize) -> &[usize] {
        let n = self.kind.num_nodes();
        &self.connectivity[e * n..(e + 1) * n]
    }

    /// The four corners of element `e`.
    pub(crate) fn corners(&self, e: usize) -> [usize; 4] {
        let nodes = self.nodes(e);
        [nodes[0], nodes[1], nodes[2], nodes[3]]
    }

    /// `integral_e L_i L_j dV` for the corners `i, j` of element `e`.
    pub(crate) fn corner_products(&self, e: usize) -> &[[f64; 4]; 4] {
        &self.corner_products[e]
    }

    /// Rest volume of element `e`, `sum_q W_q`.
    pub(crate) fn rest_volume(&self, e: usize) -> f64 {
        self.geometry.element_volume(e)
    }

    /// The global DOFs `3 * node + axis` of element `e`, node-major.
    pub(crate) fn dofs(&self, e: usize) -> impl Iterator<Item = usize> + '_ {
        self.nodes(e)
            .iter()
            .flat_map(|&i| [3 * i, 3 * i + 1, 3 * i + 2])
    }

    /// The flat node list of the elements and the nodes per element: the node blocks of
    /// [`MeasuredElements::hessian_pattern`] over every element.
    pub(crate) fn blocks(&self) -> (&[usize], usize) {
        (&self.connectivity, self.kind.num_nodes())
    }

    /// DOFs per element.
    pub(crate) fn element_dofs(&self) -> usize {
        3 * self.kind.num_nodes()
    }

    /// Checks that `x` holds one position per mesh node.
    pub(crate) fn check_positions(&self, x: &[Vec3]) -> Result<(), ConstraintError> {
        check_len("positions", self.num_nodes, x.len())
    }

    /// The rest data of element `e` for the quadrature kernel.
    fn rest_points(&self, e: usize) -> RestPoints<'_> {
        RestPoints {
            weights: self.geometry.element_weights(e),
            gradients: self.geometry.element_gradients(e),
        }
    }

    /// The rest data of point `q` of element `e` alone.
    fn rest_point(&self, e: usize, q: usize) -> RestPoints<'_> {
        let weights = self.geometry.element_weights(e);
        RestPoints {
            weights: &weights[q..q + 1],
            gradients: self.geometry.gradients(e, q),
        }
    }

    /// Mean volume ratio `J_e = sum_q W_q J_q / sum_q W_q` of element `e` (`v_e / V_e`).
    pub(crate) fn volume_ratio(&self, e: usize, x: &[Vec3]) -> f64 {
        self.deformed_volume(e, x) / self.rest_volume(e)
    }

    /// Deformed volume `sum_q W_q J_q` of element `e`.
    pub(crate) fn deformed_volume(&self, e: usize, x: &[Vec3]) -> f64 {
        let nodes = self.nodes(e);
        (0..self.geometry.num_points())
            .map(|q| {
                let f = deformation_gradient(x, nodes, self.geometry.gradients(e, q));
                self.geometry.weight(e, q) * f.determinant()
            })
            .sum()
    }

    /// The true pressure of element `e` from its multiplier `p` (see [`Measure::true_pressure`]).
    pub(crate) fn true_pressure(&self, e: usize, x: &[Vec3], p: f64) -> f64 {
        self.measure.true_pressure(p, self.volume_ratio(e, x))
    }

    /// The value `sum_j p_j L_j(xi_q)` at point `q` of element `e` of the P1 field with
    /// corner values `p` (indexed by vertex).
    pub(crate) fn corner_interpolation(&self, e: usize, q: usize, p: &[f64]) -> f64 {
        self.corners(e)
            .iter()
            .zip(&self.corner_values[q])
            .map(|(&v, l)| p[v] * l)
            .sum()
    }

    /// The shape `c_r(xi_q)` of row `r`.
    fn shape(&self, shapes: RowShape, q: usize, r: usize) -> f64 {
        match shapes {
            RowShape::One => 1.0,
            RowShape::Corners => self.corner_values[q][r],
        }
    }

    /// The quadrature kernel for element `e` and the given rest data.
    fn kernel(
        &self,
        e: usize,
        x: &[Vec3],
        rest: RestPoints<'_>,
        gradient: Option<&mut [f64]>,
        hessian: Option<&mut [f64]>,
    ) -> Result<f64, ConstraintError> {
        kernel::evaluate(&self.measure, x, self.nodes(e), rest, gradient, hessian).map_err(|err| {
            ConstraintError::NonPositiveVolumeRatio {
                element: e,
                j: err.j,
            }
        })
    }

    /// Writes the rows `m_r = sum_q W_q c_r(xi_q) Phi(J_q)` of element `e` into `out`
    /// (`shapes.rows()` entries).
    fn element_values(
        &self,
        e: usize,
        x: &[Vec3],
        shapes: RowShape,
        out: &mut [f64],
    ) -> Result<(), ConstraintError> {
        if shapes == RowShape::One {
            out[0] = self.kernel(e, x, self.rest_points(e), None, None)?;
            return Ok(());
        }
        out.fill(0.0);
        for q in 0..self.geometry.num_points() {
            let m = self.kernel(e, x, self.rest_point(e, q), None, None)?;
            for (r, o) in out.iter_mut().enumerate() {
                *o += self.shape(shapes, q, r) * m;
            }
        }
        Ok(())
    }

    /// Writes the rows of every element into `out` (`shapes.rows()` per element, element by
    /// element), in parallel. `x` must have been checked.
    pub(crate) fn fill_values(
        &self,
        x: &[Vec3],
        shapes: RowShape,
        out: &mut [f64],
    ) -> Result<(), ConstraintError> {
        check_len("element values", self.len() * shapes.rows(), out.len())?;
        out.par_chunks_mut(shapes.rows())
            .with_min_len(ELEMENTS_PER_TASK)
            .enumerate()
            .try_for_each(|(e, m)| self.element_values(e, x, shapes, m))
    }

    /// Fills `out` with Jacobian entries in blocks of `shapes.rows()` rows of
    /// [`MeasuredElements::element_dofs`]: block `b` holds the gradients `dm_r/dx` of element
    /// `e = element_of_block(b)`, in the order of [`MeasuredElements::dofs`]. `x` must have
    /// been checked.
    pub(crate) fn fill_gradients(
        &self,
        x: &[Vec3],
        shapes: RowShape,
        out: &mut [f64],
        blocks: usize,
        element_of_block: impl Fn(usize) -> usize + Sync,
    ) -> Result<(), ConstraintError> {
        let dofs = self.element_dofs();
        let rows = shapes.rows();
        check_len("jacobian buffer", blocks * rows * dofs, out.len())?;
        out.par_chunks_mut(rows * dofs)
            .with_min_len(ELEMENTS_PER_TASK)
            .enumerate()
            .try_for_each(|(b, chunk)| {
                let e = element_of_block(b);
                if shapes == RowShape::One {
                    self.kernel(e, x, self.rest_points(e), Some(chunk), None)?;
                    return Ok(());
                }
                chunk.fill(0.0);
                let mut point = vec![0.0; dofs];
                for q in 0..self.geometry.num_points() {
                    self.kernel(e, x, self.rest_point(e, q), Some(&mut point), None)?;
                    for (r, row) in chunk.chunks_exact_mut(dofs).enumerate() {
                        let c = self.shape(shapes, q, r);
                        row.iter_mut().zip(&point).for_each(|(o, g)| *o += c * g);
                    }
                }
                Ok(())
            })
    }

    /// `(dof_i, dof_j)` of the element block of every element in `elements`, row-major per
    /// block.
    pub(crate) fn hessian_pattern(
        &self,
        elements: impl Iterator<Item = usize>,
    ) -> Vec<(usize, usize)> {
        elements
            .flat_map(|e| {
                let dofs: Vec<usize> = self.dofs(e).collect();
                let columns = dofs.clone();
                dofs.into_iter()
                    .flat_map(move |r| columns.clone().into_iter().map(move |c| (r, c)))
            })
            .collect()
    }

    /// Fills `out` with geometric stiffness blocks: block `b` is
    /// `sum_q W_q p_e(xi_q) d^2 Phi(J_q)/dx^2` for `e = element_of_block(b)`, where
    /// `p_e(xi_q) = pressure(e, q)` is the multiplier field at the point, in the order of
    /// [`MeasuredElements::hessian_pattern`] (symmetric, so row- and column-major agree).
    /// `x` must have been checked.
    pub(crate) fn fill_hessians(
        &self,
        x: &[Vec3],
        out: &mut [f64],
        blocks: usize,
        element_of_block: impl Fn(usize) -> usize + Sync,
        pressure: impl Fn(usize, usize) -> f64 + Sync,
    ) -> Result<(), ConstraintError> {
        let dofs = self.element_dofs();
        check_len(
            "geometric stiffness buffer",
            blocks * dofs * dofs,
            out.len(),
        )?;
        let points = self.geometry.num_points();
        out.par_chunks_mut(dofs * dofs)
            .with_min_len(ELEMENTS_PER_TASK / 4)
            .enumerate()
            .try_for_each(|(b, chunk)| {
                let e = element_of_block(b);
                let mut weights = [0.0; MAX_POINTS];
                for (q, (w, rest)) in weights
                    .iter_mut()
                    .zip(self.geometry.element_weights(e))
                    .enumerate()
                {
                    *w = rest * pressure(e, q);
                }
                let rest = RestPoints {
                    weights: &weights[..points],
                    gradients: self.geometry.element_gradients(e),
                };
                self.kernel(e, x, rest, None, Some(chunk))?;
                Ok(())
            })
    }
}

/// The rest geometry of `mesh` at the points of `rule` (never fails on a mesh built by an
/// [`ElementMesh`] constructor, which checks every rule's points).
fn rest_geometry(mesh: &ElementMesh, rule: TetQuadrature) -> Result<RestGeometry, ConstraintError> {
    mesh.rest_geometry(rule)
        .map_err(|err| ConstraintError::InvalidMesh {
            reason: err.to_string(),
        })
}

/// The corner (barycentric) shape functions `L_j(xi)` of the reference tetrahedron.
fn corner_shapes(xi: &Vec3) -> [f64; 4] {
    let mut l = [0.0; 4];
    TetElement::Tet4.shape_values(xi, &mut l);
    l
}

/// [`ConstraintError::DimensionMismatch`] unless `actual == expected`.
pub(crate) fn check_len(
    what: &'static str,
    expected: usize,
    actual: usize,
) -> Result<(), ConstraintError> {
    if actual == expected {
        Ok(())
    } else {
        Err(ConstraintError::DimensionMismatch {
            what,
            expected,
            actual,
        })
    }
}

/// `1 / kappa_e` for one bulk modulus per element (`kappa.len()` must be the number of
/// elements), each checked by [`inverse_bulk_modulus`].
pub(crate) fn inverse_bulk_moduli(
    kappa: &[f64],
    elements: &MeasuredElements,
) -> Result<Vec<f64>, ConstraintError> {
    check_len("kappa (one per element)", elements.len(), kappa.len())?;
    kappa.iter().map(|&k| inverse_bulk_modulus(k)).collect()
}

/// `1 / kappa` for a bulk modulus `kappa > 0` (`f64::INFINITY` allowed: incompressible,
/// giving exactly zero compliance).
pub(crate) fn inverse_bulk_modulus(kappa: f64) -> Result<f64, ConstraintError> {
    if kappa > 0.0 {
        Ok(1.0 / kappa)
    } else {
        Err(ConstraintError::InvalidParameter {
            name: "kappa",
            value: kappa,
            reason: "the bulk modulus must be positive (f64::INFINITY for incompressible)",
        })
    }
}

/// Meshes for the unit tests of the constraint sets.
#[cfg(test)]
pub(crate) mod test_meshes {
    use isochor_mesh::{TetMesh, Vec3};

    /// Two tets sharing the face `(0, 1, 2)`, apexes 3 (above) and 4 (below).
    pub(crate) fn two_tets() -> TetMesh {
        let positions = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.3, 0.3, 1.0),
            Vec3::new(0.2, 0.3, -0.8),
        ];
        TetMesh::new(positions, vec![[0, 1, 2, 3], [0, 2, 1, 4]]).expect("valid mesh")
    }

    /// `x` with vertex `v` moved by `d`.
    pub(crate) fn moved(mesh: &TetMesh, v: usize, d: Vec3) -> Vec<Vec3> {
        let mut x = mesh.positions().to_vec();
        x[v] += d;
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dofs_are_node_major() {
        let mesh = ElementMesh::linear(test_meshes::two_tets());
        let elements =
            MeasuredElements::new(&mesh, TetQuadrature::Degree1, Measure::Linear).unwrap();
        let dofs: Vec<usize> = elements.dofs(1).collect();
        assert_eq!(dofs, [0, 1, 2, 6, 7, 8, 3, 4, 5, 12, 13, 14]);
        let pattern = elements.hessian_pattern([1].into_iter());
        assert_eq!(pattern.len(), 144);
        // Entry (i, j) of the block sits at 12 i + j: (dofs[1], dofs[3]).
        assert_eq!(pattern[12 + 3], (1, 6));
        // A 10-node element has 30 DOFs; its mid-edge nodes follow the 5 vertices.
        let quadratic = ElementMesh::quadratic(test_meshes::two_tets());
        let elements =
            MeasuredElements::new(&quadratic, TetQuadrature::Degree5, Measure::Linear).unwrap();
        assert_eq!(elements.element_dofs(), 30);
        assert!(elements.dofs(0).skip(12).all(|dof| dof >= 15));
    }

    #[test]
    fn every_rule_fits_the_weight_buffer() {
        assert!(TetQuadrature::ALL
            .iter()
            .all(|rule| rule.num_points() <= MAX_POINTS));
    }

    #[test]
    fn corner_products_integrate_exactly() {
        // On a 4-node tet: integral L_i L_j dV = V (1 + delta_ij) / 20.
        let mesh = test_meshes::two_tets();
        let v = mesh.rest_volumes()[0];
        let elements = MeasuredElements::new(
            &ElementMesh::linear(mesh),
            TetQuadrature::Degree1,
            Measure::Linear,
        )
        .unwrap();
        for (i, row) in elements.corner_products(0).iter().enumerate() {
            for (j, &m) in row.iter().enumerate() {
                let exact = v * if i == j { 2.0 } else { 1.0 } / 20.0;
                assert!((m - exact).abs() < 1e-16, "({i}, {j})");
            }
        }
    }

    #[test]
    fn bulk_modulus_must_be_positive() {
        assert_eq!(inverse_bulk_modulus(f64::INFINITY), Ok(0.0));
        assert_eq!(inverse_bulk_modulus(4.0), Ok(0.25));
        for bad in [0.0, -1.0, f64::NAN, f64::NEG_INFINITY] {
            assert!(matches!(
                inverse_bulk_modulus(bad),
                Err(ConstraintError::InvalidParameter { name: "kappa", .. })
            ));
        }
    }
}
