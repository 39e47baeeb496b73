//! Validation of the constraint sets: values, Jacobians and geometric stiffness against
//! finite differences for every type; the locking argument of Appendix A of Francu et al.
//! 2021 as numbers; zonal volumes; compliance limits.

use isochor_constraints::{
    Compliance, ConstraintSet, Measure, NodalCompliance, NodalConstraints, PerElementConstraints,
    ZonalConstraints,
};
use isochor_mesh::{generate::box_grid, TetMesh, Vec3, Zones};
use isochor_validation::constraint_checks::{self, jacobian, values};
use isochor_validation::fd;
use isochor_validation::strategies::{deformed_box, two_tets, Deformed};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

/// Finite-difference agreement required of every derivative. The differences step by
/// `fd::STEP` (1e-6) on unit-sized meshes whose tets keep at least 0.3 of their volume: the
/// volumes are cubic in `x`, so the truncation is about `STEP^2 / J^2 ~ 1e-11` (the
/// logarithmic measure's `log J` included), and the rounding `eps / STEP ~ 1e-10`; the
/// largest error measured over these cases is 9.5e-10.
const FD_TOLERANCE: f64 = 1e-6;

/// `m_e = V_e Phi(J_e)` of every tet, from the mesh crate's volumes: the reference that the
/// constraint values are checked against.
fn element_measures(mesh: &TetMesh, x: &[Vec3], measure: Measure) -> Vec<f64> {
    let rest = mesh.rest_volumes();
    (0..mesh.num_tets())
        .map(|e| {
            let v = mesh.volume_at(e, x);
            match measure {
                Measure::Linear => v - rest[e],
                Measure::Logarithmic => rest[e] * (v / rest[e]).ln(),
            }
        })
        .collect()
}

/// Overlapping test zones: everything, the tets with centroid left of the middle, and
/// every other tet (which overlaps both).
fn test_zones(mesh: &TetMesh) -> Zones {
    let (lo, hi) = mesh.bounding_box();
    let mid = 0.5 * (lo.x + hi.x);
    let all: Vec<usize> = (0..mesh.num_tets()).collect();
    let left = all
        .iter()
        .copied()
        .filter(|&e| mesh.centroid(e).x < mid)
        .collect();
    let even = all.iter().copied().filter(|e| e % 2 == 0).collect();
    Zones::from_sets(vec![all, left, even])
}

/// An independent computation of a constraint set's values.
type Reference = Box<dyn Fn(&TetMesh, &[Vec3]) -> DVector<f64>>;

/// A constraint set under test with an independent computation of its values.
struct Case {
    set: Box<dyn ConstraintSet>,
    reference: Reference,
}

/// Every constraint type on `mesh`: P0 and P1 with both measures, and zonal with
/// overlapping zones.
fn all_cases(mesh: &TetMesh) -> Vec<Case> {
    let mut cases = Vec::new();
    for measure in [Measure::Linear, Measure::Logarithmic] {
        cases.push(Case {
            set: Box::new(PerElementConstraints::new(mesh, measure, 10.0).expect("P0")),
            reference: Box::new(move |mesh, x| {
                DVector::from_vec(element_measures(mesh, x, measure))
            }),
        });
        cases.push(Case {
            set: Box::new(
                NodalConstraints::new(mesh, measure, 10.0, NodalCompliance::Consistent)
                    .expect("P1"),
            ),
            reference: Box::new(move |mesh, x| {
                let mut phi = DVector::zeros(mesh.num_vertices());
                for (m, tet) in element_measures(mesh, x, measure).iter().zip(mesh.tets()) {
                    tet.iter().for_each(|&v| phi[v] += m / 4.0);
                }
                phi
            }),
        });
    }
    let zones = test_zones(mesh);
    cases.push(Case {
        set: Box::new(ZonalConstraints::new(mesh, &zones).expect("zonal")),
        reference: Box::new(move |mesh, x| {
            let m = element_measures(mesh, x, Measure::Linear);
            DVector::from_iterator(
                zones.len(),
                zones.iter().map(|z| z.iter().map(|&e| m[e]).sum()),
            )
        }),
    });
    cases
}

/// The generic harness: `phi` against the reference, and `G` and `K_g` against central
/// differences ([`constraint_checks::derivative_errors`]); `K_g` must be symmetric.
fn check_case(case: &Case, deformed: &Deformed, p: &[f64]) -> Result<(), TestCaseError> {
    let set = case.set.as_ref();
    let name = set.name();
    let x = &deformed.x;

    let phi = values(set, x);
    let phi_ref = (case.reference)(&deformed.mesh, x);
    let err = fd::relative_error_vec(&phi, &phi_ref, 1e-12);
    prop_assert!(
        err < 1e-12,
        "{name}: phi differs from the reference by {err:e}"
    );

    let errors = constraint_checks::derivative_errors(set, x, p, 1.0);
    prop_assert!(
        errors.jacobian < FD_TOLERANCE,
        "{name}: G vs finite differences {:e}",
        errors.jacobian
    );
    prop_assert!(
        errors.geometric_stiffness < FD_TOLERANCE,
        "{name}: K_g vs finite differences {:e}",
        errors.geometric_stiffness
    );
    prop_assert!(errors.asymmetry <= 1e-14);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn derivatives_on_two_tets(
        deformed in two_tets(0.1, 0.2, 0.3),
        p in proptest::collection::vec(-1.0..1.0f64, 8),
    ) {
        for case in all_cases(&deformed.mesh) {
            check_case(&case, &deformed, &p)?;
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn derivatives_on_a_box(
        deformed in deformed_box([2, 2, 2], 0.06, 0.3),
        p in proptest::collection::vec(-1.0..1.0f64, 48),
    ) {
        for case in all_cases(&deformed.mesh) {
            check_case(&case, &deformed, &p)?;
        }
    }

    #[test]
    fn zone_volume_from_boundary_faces_equals_element_sum(
        deformed in deformed_box([3, 2, 2], 0.1, 0.1),
    ) {
        let zones = test_zones(&deformed.mesh);
        let set = ZonalConstraints::new(&deformed.mesh, &zones).expect("zonal");
        for z in 0..zones.len() {
            let by_tets = set.zone_volume(z, &deformed.x).expect("zone volume");
            let by_faces = set.zone_boundary_volume(z, &deformed.x).expect("boundary volume");
            prop_assert!((by_tets - by_faces).abs() <= 1e-13 * by_tets.abs(),
                "zone {z}: {by_tets} by tets, {by_faces} by faces");
        }
        // The whole box has 2 (4 + 6 + 6) square boundary faces, two triangles each.
        prop_assert_eq!(set.boundary(0).expect("zone 0").len(), 2 * 2 * (6 + 4 + 6));
    }
}

fn scientific(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|v| format!("{v:.3e}")).collect();
    format!("[{}]", items.join(", "))
}

/// Rank and null space of `G` restricted to the free DOFs, from its SVD.
struct Spectrum {
    /// Singular values, descending.
    singular_values: Vec<f64>,
    rank: usize,
    /// Orthonormal basis of the row space (rows of `V^T` with nonzero singular values).
    row_space: DMatrix<f64>,
}

impl Spectrum {
    fn new(g: DMatrix<f64>) -> Self {
        let svd = g.svd(false, true);
        let singular_values = svd.singular_values.as_slice().to_vec();
        let tolerance = 1e-10 * singular_values[0];
        let rank = singular_values.iter().filter(|&&s| s > tolerance).count();
        let v_t = svd.v_t.expect("V^T was requested");
        Spectrum {
            singular_values,
            rank,
            row_space: v_t.rows(0, rank).into_owned(),
        }
    }

    fn null_dimension(&self) -> usize {
        self.row_space.ncols() - self.rank
    }

    fn smallest_nonzero(&self) -> f64 {
        self.singular_values[self.rank - 1]
    }

    /// `|u - P u| / |u|` with `P` the projection onto the null space of `G`: how much of `u`
    /// no volume-preserving discrete motion can represent (the row-space component).
    fn missed_fraction(&self, u: &DVector<f64>) -> f64 {
        (&self.row_space * u).norm() / u.norm()
    }
}

/// Appendix A of Francu et al. 2021 made concrete on a 4x3x3-cell box of unit cells clamped on
/// its `x = 0` face: linearized incompressibility is `G u = 0` on the free DOFs, and a
/// discretization locks when the discrete volume-preserving motions (the null space of `G`)
/// cannot represent the deformations the body needs.
///
/// The test does not claim that only `u = 0` preserves every element volume: the two linear
/// shears `u = (0, a x, b x)` vanish on the clamped face, are isochoric and are interpolated
/// exactly, so they preserve every tet's volume in any discretization; free-surface vertices
/// add local mechanisms, and the structured (Kuhn) split has many dependent element
/// constraints (rank 132 of 216). Instead it measures what locking means: the share of a
/// smooth divergence-free bending field `u = (x^2, -2 x (y - c), 0) / L` that lies outside
/// the volume-preserving motions. (4x3x3 rather than 4x2x2 cells, so that P0 counts more
/// constraints than free DOFs, violating eq. 1.)
#[test]
fn appendix_a_element_constraints_lock_nodal_ones_do_not() {
    let cells = [4, 3, 3];
    let extent = Vec3::new(4.0, 3.0, 3.0);
    let grid = box_grid(Vec3::zeros(), extent, cells).expect("box");
    let clamped = |v: usize| grid.positions()[v].x <= 1e-12;
    // A deterministic jitter of the free vertices by up to 0.15 cell, to rule out effects
    // of the structured split.
    let jitter =
        |v: usize, k: usize| (((v * 7919 + k * 104_729) % 1009) as f64 / 1009.0 - 0.5) * 0.3;
    let jittered: Vec<Vec3> = (0..grid.num_vertices())
        .map(|v| {
            let offset = Vec3::new(jitter(v, 0), jitter(v, 1), jitter(v, 2));
            grid.positions()[v] + if clamped(v) { Vec3::zeros() } else { offset }
        })
        .collect();
    let meshes = [
        ("structured", grid.clone()),
        (
            "jittered",
            TetMesh::new(jittered, grid.tets().to_vec()).expect("jittered box"),
        ),
    ];
    let free_vertices: Vec<usize> = (0..grid.num_vertices()).filter(|&v| !clamped(v)).collect();
    let free_dofs: Vec<usize> = free_vertices
        .iter()
        .flat_map(|&v| (0..3).map(move |k| 3 * v + k))
        .collect();
    let n_free = free_dofs.len();

    for (label, mesh) in &meshes {
        let x = mesh.positions();
        let field = |f: &dyn Fn(Vec3) -> Vec3| {
            DVector::from_iterator(
                n_free,
                free_vertices.iter().flat_map(|&v| f(x[v]).data.0[0]),
            )
        };
        let c = 0.5 * extent.y;
        let bending = field(&|p| Vec3::new(p.x * p.x, -2.0 * p.x * (p.y - c), 0.0) / extent.x);
        let shear = field(&|p| Vec3::new(0.0, 0.3 * p.x, -0.2 * p.x));

        let p0 = PerElementConstraints::new(mesh, Measure::Linear, f64::INFINITY).expect("P0");
        let p1 = NodalConstraints::new(
            mesh,
            Measure::Linear,
            f64::INFINITY,
            NodalCompliance::Lumped,
        )
        .expect("P1");
        let n_p0 = p0.num_constraints();
        let n_p1 = p1.num_constraints();
        let s0 = Spectrum::new(jacobian(&p0, x).select_columns(&free_dofs));
        let s1 = Spectrum::new(jacobian(&p1, x).select_columns(&free_dofs));
        let (missed0, missed1) = (s0.missed_fraction(&bending), s1.missed_fraction(&bending));
        let (shear0, shear1) = (s0.missed_fraction(&shear), s1.missed_fraction(&shear));
        println!("{label} box {cells:?}, x = 0 clamped: {n_free} free DOFs");
        println!(
            "  P0: n_p = {n_p0}, rank {}, null space {}, smallest nonzero singular value {:.3e} \
             (largest {:.3e}), smallest three {}; bending missed {missed0:.3}, shear missed {shear0:.1e}",
            s0.rank,
            s0.null_dimension(),
            s0.smallest_nonzero(),
            s0.singular_values[0],
            scientific(&s0.singular_values[n_free - 3..]),
        );
        println!(
            "  P1: n_p = {n_p1}, rank {}, null space {} (>= n_x - n_p = {}), smallest nonzero \
             singular value {:.3e}, smallest three {}; bending missed {missed1:.3}, shear missed {shear1:.1e}",
            s1.rank,
            s1.null_dimension(),
            n_free - n_p1,
            s1.smallest_nonzero(),
            scientific(&s1.singular_values[n_p1 - 3..]),
        );

        // Counting (eq. 1): P0 over-constrains, P1 leaves room.
        assert!(n_p0 > n_free && n_p1 < n_free);
        assert!(s1.null_dimension() >= n_free - n_p1);
        // The 3 spurious pressure modes of the nodal Jacobian (docs/toolchain.md) persist
        // under clamping: they depend on the connectivity only.
        assert_eq!(s1.rank, n_p1 - 3, "{label}");
        assert!(s0.null_dimension() < s1.null_dimension());
        // Both keep the exact linear shears.
        assert!(
            shear0 < 1e-9 && shear1 < 1e-9,
            "{label}: {shear0:e} {shear1:e}"
        );
        // Locking: P0 cannot follow a smooth bending deformation, P1 nearly can.
        assert!(missed0 > 0.3, "{label}: P0 missed only {missed0}");
        assert!(missed1 < 0.1, "{label}: P1 missed {missed1}");
        assert!(missed0 > 5.0 * missed1, "{label}");
    }
}

/// On a structured box without boundary conditions the nodal Jacobian has exactly 3 zero
/// singular values (spurious pressure modes, docs/toolchain.md).
#[test]
fn nodal_jacobian_of_a_free_box_has_three_spurious_pressure_modes() {
    let mesh = box_grid(Vec3::zeros(), Vec3::new(4.0, 3.0, 3.0), [4, 3, 3]).expect("box");
    let p1 =
        NodalConstraints::new(&mesh, Measure::Linear, 1.0, NodalCompliance::Lumped).expect("P1");
    let s = Spectrum::new(jacobian(&p1, mesh.positions()).transpose());
    let n = p1.num_constraints();
    println!(
        "free 4x3x3 box: nodal G has {n} rows, rank {}, smallest four singular values {}",
        s.rank,
        scientific(&s.singular_values[n - 4..])
    );
    assert_eq!(s.rank, n - 3);
}

#[test]
fn zonal_constraints_vanish_at_rest_and_overlapping_zones_are_independent() {
    let mesh = box_grid(Vec3::zeros(), Vec3::new(2.0, 1.0, 1.0), [4, 2, 2]).expect("box");
    let all: Vec<usize> = (0..mesh.num_tets()).collect();
    let left: Vec<usize> = all
        .iter()
        .copied()
        .filter(|&e| mesh.centroid(e).x < 1.0)
        .collect();
    let zones = Zones::from_sets(vec![all, left]);
    let set = ZonalConstraints::new(&mesh, &zones).expect("zonal");
    let phi = values(&set, mesh.positions());
    assert!(phi.amax() <= 1e-15 * mesh.rest_volume(), "{phi}");
    assert_eq!(set.compliance(), Compliance::Diagonal(vec![0.0, 0.0]));
    let s = Spectrum::new(jacobian(&set, mesh.positions()));
    println!(
        "global + half zone: singular values {}",
        scientific(&s.singular_values)
    );
    assert_eq!(s.rank, 2);
    assert!(s.singular_values[1] > 1e-2 * s.singular_values[0]);
}

#[test]
fn compliance_limits() {
    let mesh = box_grid(Vec3::zeros(), Vec3::repeat(1.0), [2, 2, 2]).expect("box");
    let n = mesh.num_vertices();
    let nodal = |kappa, kind| {
        NodalConstraints::new(&mesh, Measure::Linear, kappa, kind)
            .expect("P1")
            .compliance()
    };
    // kappa = inf: exactly zero, every entry, every variant.
    let zero = |c: Compliance| match c {
        Compliance::Diagonal(d) => d.iter().all(|&v| v == 0.0),
        Compliance::Sparse(t) => t.iter().all(|&(_, _, v)| v == 0.0),
    };
    assert!(zero(nodal(f64::INFINITY, NodalCompliance::Lumped)));
    assert!(zero(nodal(f64::INFINITY, NodalCompliance::Consistent)));
    assert!(zero(
        PerElementConstraints::new(&mesh, Measure::Logarithmic, f64::INFINITY)
            .expect("P0")
            .compliance()
    ));
    assert!(zero(
        ZonalConstraints::new(&mesh, &Zones::from_sets(vec![vec![0, 1, 2]]))
            .expect("zonal")
            .with_bulk_modulus(f64::INFINITY)
            .expect("kappa = inf")
            .compliance()
    ));
    // Consistent row sums equal the lumped diagonal, whose sum is the body volume / kappa.
    let kappa = 7.0;
    let Compliance::Diagonal(lumped) = nodal(kappa, NodalCompliance::Lumped) else {
        panic!("lumped compliance is diagonal");
    };
    let Compliance::Sparse(consistent) = nodal(kappa, NodalCompliance::Consistent) else {
        panic!("consistent compliance is sparse");
    };
    let mut row_sums = vec![0.0; n];
    consistent.iter().for_each(|&(i, _, v)| row_sums[i] += v);
    for (v, (sum, diagonal)) in row_sums.iter().zip(&lumped).enumerate() {
        assert!(
            (sum - diagonal).abs() <= 1e-14 * diagonal,
            "vertex {v}: {sum} vs {diagonal}"
        );
    }
    let total: f64 = lumped.iter().sum();
    assert!((total - mesh.rest_volume() / kappa).abs() < 1e-15);
    for bad in [0.0, -1.0, f64::NAN] {
        assert!(
            NodalConstraints::new(&mesh, Measure::Linear, bad, NodalCompliance::Lumped).is_err()
        );
    }
}
