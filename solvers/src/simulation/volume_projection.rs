//! Volume projections after each implicit Euler step: the two baselines Sheen et al. 2021
//! compare their method against in Fig. 8 (sec. 8.3), applied to the state the step's Newton
//! solve accepted (the equations: [`VolumeProjection`]).

use crate::error::SolverError;
use crate::linear::{max_abs_diagonal, CholeskySolver, Ordering};
use crate::model::dofs::Dofs;
use crate::model::row_volumes;
use crate::settings::VolumeProjection;
use faer::sparse::{SparseColMat, Triplet};
use isochor_constraints::{
    exact_rule, jacobian_matrix, ConstraintSet, Measure, NodalCompliance, NodalConstraints,
    RowShape,
};
use isochor_mesh::{ElementMesh, Vec3};

/// Relative diagonal shift of the pressure matrix (see [`VolumeProjection`]).
const PRESSURE_SHIFT: f64 = 1e-8;

/// Stop the rescaling's secant iterations at this volume error, relative to the rest volume
/// (a few roundings of a sum over the elements).
const RESCALE_TOLERANCE: f64 = 1e-12;

/// Most secant iterations of the rescaling (a cubic from a start within a few percent
/// converges in a handful).
const RESCALE_ITERATIONS: usize = 50;

/// A [`VolumeProjection`] set up on a mesh.
#[derive(Debug)]
pub struct VolumeProjector {
    kind: Kind,
    /// Inverse lumped mass of every DOF (`3 node + axis`), zero where prescribed.
    inverse_masses: Vec<f64>,
    ordering: Ordering,
}

#[derive(Debug)]
enum Kind {
    None,
    OneRing {
        constraints: Box<NodalConstraints>,
        /// `V0_i` per vertex.
        rest: Vec<f64>,
        recovery: f64,
    },
    GlobalRescale {
        rest_volume: f64,
    },
}

impl VolumeProjector {
    /// `projection` on `mesh` with lumped `masses` (one per node) and the DOFs `dofs`; pressure
    /// matrices are factored under `ordering`.
    ///
    /// Errors: a bad recovery.
    pub fn new(
        projection: VolumeProjection,
        mesh: &ElementMesh,
        masses: &[f64],
        dofs: &Dofs,
        ordering: Ordering,
    ) -> Result<Self, SolverError> {
        projection.validate()?;
        let inverse_masses = (0..3 * masses.len())
            .map(|dof| match dofs.free_index(dof) {
                Some(_) if masses[dof / 3] > 0.0 => 1.0 / masses[dof / 3],
                _ => 0.0,
            })
            .collect();
        let kind = match projection {
            VolumeProjection::None => Kind::None,
            VolumeProjection::OneRing { recovery } => {
                let constraints = NodalConstraints::on_elements(
                    mesh,
                    exact_rule(mesh.kind(), RowShape::Corners),
                    Measure::Linear,
                    f64::INFINITY,
                    NodalCompliance::Lumped,
                )?;
                let rest = row_volumes(&constraints, mesh.nodes())?
                    .iter()
                    .map(|v| 4.0 * v)
                    .collect();
                Kind::OneRing {
                    constraints: Box::new(constraints),
                    rest,
                    recovery,
                }
            }
            VolumeProjection::GlobalRescale => Kind::GlobalRescale {
                rest_volume: mesh.total_volume_at(mesh.nodes()),
            },
        };
        Ok(VolumeProjector {
            kind,
            inverse_masses,
            ordering,
        })
    }

    /// Corrects the positions `x` and velocities `v` of an accepted step of length `dt`.
    pub fn apply(
        &self,
        mesh: &ElementMesh,
        x: &mut [Vec3],
        v: &mut [Vec3],
        dt: f64,
    ) -> Result<(), SolverError> {
        match &self.kind {
            Kind::None => Ok(()),
            Kind::OneRing {
                constraints,
                rest,
                recovery,
            } => {
                let volumes = one_ring_volumes(constraints, rest, x)?;
                let d: Vec<f64> = volumes
                    .iter()
                    .zip(rest)
                    .map(|(volume, v0)| (v0 - volume).clamp(-recovery * v0, recovery * v0))
                    .collect();
                let dx = self.pressure_correction(constraints, x, &d, dt)?;
                x.iter_mut().zip(&dx).for_each(|(xi, d)| *xi += d);
                let g = gradient(constraints, x)?;
                let rate: Vec<f64> = (0..g.rows())
                    .map(|i| {
                        let row = g.outer_view(i).expect("a row of G");
                        -dt * row
                            .iter()
                            .map(|(dof, gi)| gi * v[dof / 3][dof % 3])
                            .sum::<f64>()
                    })
                    .collect();
                let dv = self.pressure_correction(constraints, x, &rate, dt)?;
                v.iter_mut().zip(&dv).for_each(|(vi, d)| *vi += d / dt);
                Ok(())
            }
            Kind::GlobalRescale { rest_volume } => self.rescale(mesh, x, *rest_volume),
        }
    }

    /// `dt^2 W G^T p` per node with `A p = rhs`, `A = dt^2 G W G^T` at `x` (see
    /// [`VolumeProjection`]).
    fn pressure_correction(
        &self,
        constraints: &NodalConstraints,
        x: &[Vec3],
        rhs: &[f64],
        dt: f64,
    ) -> Result<Vec<Vec3>, SolverError> {
        let linear = |e: crate::linear::LinearError| SolverError::Linear(e.to_string());
        let g = gradient(constraints, x)?.to_csc();
        let w = &self.inverse_masses;
        let mut triplets = Vec::new();
        for (dof, column) in g.outer_iterator().enumerate() {
            if w[dof] == 0.0 {
                continue;
            }
            for (i, gi) in column.iter() {
                for (j, gj) in column.iter().filter(|&(j, _)| j <= i) {
                    triplets.push(Triplet::new(i, j, dt * dt * gi * gj * w[dof]));
                }
            }
        }
        let m = g.rows();
        triplets.extend((0..m).map(|i| Triplet::new(i, i, 0.0)));
        let a = SparseColMat::try_new_from_triplets(m, m, &triplets)
            .map_err(|e| SolverError::Linear(format!("{e:?}")))?;
        // A one ring nothing can move keeps its volume: zero pressure.
        let diagonal = diagonal(&a);
        let mut p: Vec<f64> = rhs
            .iter()
            .zip(&diagonal)
            .map(|(r, &aii)| if aii > 0.0 { *r } else { 0.0 })
            .collect();
        let mut cholesky =
            CholeskySolver::with_ordering(a.symbolic(), self.ordering).map_err(linear)?;
        cholesky
            .factorize(a.as_ref(), PRESSURE_SHIFT * max_abs_diagonal(a.as_ref()))
            .map_err(linear)?;
        cholesky.solve_in_place(&mut p).map_err(linear)?;
        let mut dx = vec![Vec3::zeros(); x.len()];
        for (dof, column) in g.outer_iterator().enumerate() {
            let force: f64 = column.iter().map(|(i, gi)| gi * p[i]).sum();
            dx[dof / 3][dof % 3] = dt * dt * w[dof] * force;
        }
        Ok(dx)
    }

    /// Scales the free DOFs about their centre of mass to the volume `rest_volume`.
    fn rescale(
        &self,
        mesh: &ElementMesh,
        x: &mut [Vec3],
        rest_volume: f64,
    ) -> Result<(), SolverError> {
        let w = &self.inverse_masses;
        let mut centre = Vec3::zeros();
        for axis in 0..3 {
            let (mut mass, mut moment) = (0.0, 0.0);
            for (node, p) in x.iter().enumerate() {
                let wi = w[3 * node + axis];
                if wi > 0.0 {
                    mass += 1.0 / wi;
                    moment += p[axis] / wi;
                }
            }
            centre[axis] = if mass > 0.0 { moment / mass } else { 0.0 };
        }
        let start = x.to_vec();
        let scaled = |s: f64, out: &mut [Vec3]| {
            for (dof, &wi) in w.iter().enumerate() {
                let (node, axis) = (dof / 3, dof % 3);
                if wi > 0.0 {
                    out[node][axis] = centre[axis] + s * (start[node][axis] - centre[axis]);
                }
            }
        };
        let error = |out: &[Vec3]| mesh.total_volume_at(out) - rest_volume;
        let (mut s0, mut f0) = (1.0, error(x));
        if f0.abs() <= RESCALE_TOLERANCE * rest_volume {
            return Ok(());
        }
        let mut s1 = (rest_volume / mesh.total_volume_at(x)).cbrt();
        for _ in 0..RESCALE_ITERATIONS {
            scaled(s1, x);
            let f1 = error(x);
            if !f1.is_finite() {
                return Err(SolverError::NonFinite("the rescaled volume"));
            }
            if f1.abs() <= RESCALE_TOLERANCE * rest_volume {
                return Ok(());
            }
            (s0, f0, s1) = (s1, f1, s1 - f1 * (s1 - s0) / (f1 - f0));
        }
        Err(SolverError::InvalidProblem(format!(
            "the global rescaling did not reach the rest volume in {RESCALE_ITERATIONS} iterations (volume error {:e})",
            error(x)
        )))
    }
}

/// `V_i(x)` per vertex: the rest volumes plus four times the nodal constraint values.
fn one_ring_volumes(
    constraints: &NodalConstraints,
    rest: &[f64],
    x: &[Vec3],
) -> Result<Vec<f64>, SolverError> {
    let mut phi = vec![0.0; constraints.num_constraints()];
    constraints.values(x, &mut phi)?;
    Ok(phi.iter().zip(rest).map(|(p, v0)| v0 + 4.0 * p).collect())
}

/// `G = dV/dx` at `x` (CSR, one row per vertex): four times the nodal constraints' Jacobian.
fn gradient(
    constraints: &NodalConstraints,
    x: &[Vec3],
) -> Result<isochor_constraints::SparseMatrix, SolverError> {
    let mut g = jacobian_matrix(constraints, x)?;
    g.data_mut().iter_mut().for_each(|v| *v *= 4.0);
    Ok(g)
}

/// The diagonal of a square matrix (zero where it has no entry).
fn diagonal(a: &SparseColMat<usize, f64>) -> Vec<f64> {
    let a = a.as_ref();
    (0..a.ncols())
        .map(|c| {
            a.row_idx_of_col(c)
                .zip(a.val_of_col(c))
                .filter(|(r, _)| *r == c)
                .map(|(_, v)| *v)
                .sum()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::loads::{Dirichlet, Motion};
    use isochor_mesh::generate::box_grid;
    use isochor_mesh::shape_matrix;
    use nalgebra::{DMatrix, SymmetricEigen};

    const DT: f64 = 0.008;

    /// The unit cube in 2^3 cells of 6 tets (27 vertices).
    fn cube() -> ElementMesh {
        ElementMesh::linear(box_grid(Vec3::zeros(), Vec3::repeat(1.0), [2, 2, 2]).unwrap())
    }

    /// Unequal masses, so that a wrong mass weighting shows.
    fn masses(n: usize) -> Vec<f64> {
        (0..n).map(|i| 1.0 + 0.5 * (i as f64).sin()).collect()
    }

    fn projector(
        projection: VolumeProjection,
        mesh: &ElementMesh,
        fixed: &[usize],
    ) -> VolumeProjector {
        let conditions = [Dirichlet {
            nodes: fixed.to_vec(),
            axes: [true; 3],
            motion: Motion::Fixed,
            curve: None,
        }];
        let dofs = Dofs::new(mesh.num_nodes(), &conditions).unwrap();
        VolumeProjector::new(
            projection,
            mesh,
            &masses(mesh.num_nodes()),
            &dofs,
            Ordering::Amd,
        )
        .unwrap()
    }

    /// A velocity field that changes the one-ring volumes.
    fn swirl(x: &[Vec3]) -> Vec<Vec3> {
        x.iter()
            .map(|p| Vec3::new(p.x.sin(), (2.0 * p.y).cos(), p.z * p.x))
            .collect()
    }

    /// How far a solve with the shifted pressure matrix may miss its right-hand side `b`
    /// (2-norm): `A p = b - s p`, so the miss is `s |(A + s)^-1 b| <= s / lambda_min |b|`,
    /// `lambda_min` the smallest nonzero eigenvalue of `A` (its zero ones, the spurious
    /// modes, are orthogonal to every right-hand side of these tests).
    fn shift_miss(p: &VolumeProjector, x: &[Vec3], b: &[f64]) -> f64 {
        let Kind::OneRing { constraints, .. } = &p.kind else {
            unreachable!()
        };
        let sparse = gradient(constraints, x).unwrap();
        let mut g = DMatrix::zeros(sparse.rows(), sparse.cols());
        for (value, (i, j)) in sparse.iter() {
            g[(i, j)] += value;
        }
        let w = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(p.inverse_masses.clone()));
        let a = DT * DT * &g * w * g.transpose();
        let s = PRESSURE_SHIFT * a.diagonal().amax();
        let eigen = SymmetricEigen::new(a);
        let largest = eigen.eigenvalues.amax();
        let smallest = eigen
            .eigenvalues
            .iter()
            .filter(|&&l| l > 1e-12 * largest)
            .fold(f64::INFINITY, |a, &b| a.min(b));
        s / smallest * b.iter().map(|v| v * v).sum::<f64>().sqrt()
    }

    /// Bound on `V_e(x + dx) - V_e(x) - dV_e/dx dx` summed over each vertex's one ring:
    /// `V_e(x + dx) = V_e det(I + H)`, `H = D_s(dx) D_s(x)^-1`, whose terms beyond `tr H` are
    /// `sigma_2(H) + det H`, at most `2 |H|^2 + |H|^3` (Frobenius norm).
    fn second_order(mesh: &ElementMesh, x: &[Vec3], dx: &[Vec3]) -> Vec<f64> {
        let corners = mesh.corners();
        let mut bound = vec![0.0; corners.num_vertices()];
        for (e, tet) in corners.tets().iter().enumerate() {
            let ds = shape_matrix(tet.map(|v| &x[v]));
            let h = shape_matrix(tet.map(|v| &dx[v])) * ds.try_inverse().unwrap();
            let n = h.norm();
            let term = corners.volume_at(e, x) * (2.0 * n * n + n * n * n);
            tet.iter().for_each(|&v| bound[v] += term);
        }
        bound
    }

    /// Irving et al. 2007's projection ([`VolumeProjection`]) on a free cube squashed along z: every
    /// one-ring volume moves towards its rest volume by the clamped target `d_i` (all of the
    /// 3% deficit with recovery 5%, 1% of the rest volume with recovery 1%), to within the
    /// linearization's second-order terms and the pressure shift's miss; the corrected
    /// velocities then change no one-ring volume (`G v = 0`) to within the shift's miss.
    #[test]
    fn one_ring_projection_recovers_the_clamped_volume_and_projects_the_velocities() {
        let mesh = cube();
        let squashed: Vec<Vec3> = mesh
            .nodes()
            .iter()
            .map(|p| Vec3::new(p.x, p.y, 0.97 * p.z))
            .collect();
        for recovery in [0.05, 0.01] {
            let p = projector(VolumeProjection::OneRing { recovery }, &mesh, &[]);
            let Kind::OneRing {
                constraints, rest, ..
            } = &p.kind
            else {
                unreachable!()
            };
            let before = one_ring_volumes(constraints, rest, &squashed).unwrap();
            let d: Vec<f64> = before
                .iter()
                .zip(rest)
                .map(|(v, v0)| (v0 - v).min(recovery * v0))
                .collect();
            let (mut x, mut v) = (squashed.clone(), swirl(&squashed));
            p.apply(&mesh, &mut x, &mut v, DT).unwrap();
            let after = one_ring_volumes(constraints, rest, &x).unwrap();
            let dx: Vec<Vec3> = x.iter().zip(&squashed).map(|(a, b)| a - b).collect();
            let bound = second_order(&mesh, &squashed, &dx);
            let miss = shift_miss(&p, &squashed, &d);
            eprintln!(
                "recovery {recovery}: largest |change - d| / d {:.2e}, its bound {:.2e}, shift miss {miss:.1e}",
                (0..rest.len())
                    .map(|i| (after[i] - before[i] - d[i]).abs() / d[i])
                    .fold(0.0, f64::max),
                (0..rest.len()).map(|i| bound[i] / d[i]).fold(0.0, f64::max),
            );
            for i in 0..rest.len() {
                let change = after[i] - before[i];
                assert!(
                    (change - d[i]).abs() <= bound[i] + miss,
                    "recovery {recovery}, vertex {i}: change {change:e}, target {:e}, bound {:e}",
                    d[i],
                    bound[i] + miss
                );
                assert!((after[i] - rest[i]).abs() < (before[i] - rest[i]).abs());
            }
            let g = gradient(constraints, &x).unwrap();
            let rate = |v: &[Vec3]| -> Vec<f64> {
                (0..g.rows())
                    .map(|i| {
                        let row = g.outer_view(i).unwrap();
                        row.iter().map(|(dof, gi)| gi * v[dof / 3][dof % 3]).sum()
                    })
                    .collect()
            };
            let b: Vec<f64> = rate(&swirl(&squashed)).iter().map(|r| -DT * r).collect();
            let miss = shift_miss(&p, &x, &b) / DT;
            let residual = rate(&v).iter().map(|r| r * r).sum::<f64>().sqrt();
            assert!(
                residual <= miss,
                "recovery {recovery}: |G v| = {residual:e} > {miss:e}"
            );
        }
    }

    /// At rest, at rest volumes and without motion, neither projection changes anything.
    #[test]
    fn a_rest_state_is_a_fixed_point_of_both_projections() {
        let mesh = cube();
        for projection in [
            VolumeProjection::OneRing { recovery: 0.01 },
            VolumeProjection::GlobalRescale,
        ] {
            let p = projector(projection, &mesh, &[]);
            let (mut x, mut v) = (mesh.nodes().to_vec(), vec![Vec3::zeros(); mesh.num_nodes()]);
            p.apply(&mesh, &mut x, &mut v, DT).unwrap();
            assert_eq!(x, mesh.nodes(), "{projection:?}");
            assert!(v.iter().all(|v| *v == Vec3::zeros()), "{projection:?}");
        }
    }

    /// The global rescaling of a deformed cube, free and with its base held: the total volume
    /// equals the rest volume to the secant iterations' tolerance, the free DOFs' centre of
    /// mass stays where it was (to rounding of sums of 27 coordinates of order 1), the held
    /// vertices and the velocities are untouched.
    #[test]
    fn global_rescale_restores_the_rest_volume_about_the_centre_of_mass() {
        let mesh = cube();
        let rest_volume = mesh.total_volume_at(mesh.nodes());
        let deformed: Vec<Vec3> = mesh
            .nodes()
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let wobble = 0.02 * (3.0 * i as f64).sin();
                Vec3::new(0.95 * p.x + wobble, p.y, 0.9 * p.z + p.z * wobble)
            })
            .collect();
        let base: Vec<usize> = (0..mesh.num_nodes())
            .filter(|&i| mesh.nodes()[i].z == 0.0)
            .collect();
        for fixed in [vec![], base] {
            let p = projector(VolumeProjection::GlobalRescale, &mesh, &fixed);
            let free: Vec<usize> = (0..mesh.num_nodes())
                .filter(|i| !fixed.contains(i))
                .collect();
            let centre = |x: &[Vec3]| -> Vec3 {
                let m = masses(x.len());
                let total: f64 = free.iter().map(|&i| m[i]).sum();
                free.iter().map(|&i| m[i] * x[i]).sum::<Vec3>() / total
            };
            let (mut x, mut v) = (deformed.clone(), swirl(&deformed));
            p.apply(&mesh, &mut x, &mut v, DT).unwrap();
            let volume = mesh.total_volume_at(&x);
            assert!(
                (volume - rest_volume).abs() <= RESCALE_TOLERANCE * rest_volume,
                "{} held: volume {volume} vs {rest_volume}",
                fixed.len()
            );
            assert!((centre(&x) - centre(&deformed)).norm() <= 1e-14);
            assert!(fixed.iter().all(|&i| x[i] == deformed[i]));
            assert_eq!(v, swirl(&deformed));
            assert!((mesh.total_volume_at(&deformed) - rest_volume).abs() > 0.05 * rest_volume);
        }
    }
}
