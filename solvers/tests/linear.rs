//! Tests of the linear-algebra layer against dense nalgebra references, and on a P1-P1
//! saddle point of a structured tet box at `C = 0` (exactly singular KKT).

use crate::common;

use common::{p1_box, P1Box, Rng};
use faer::sparse::SparseColMat;
use isochor_solvers::linear::{
    cg, diagonal, minres, relative_residual, saddle_point_diagonal, CholeskySolver, Factorization,
    IterativeOptions, Jacobi, KktOptions, KktSolver, LinearError, LinearOperator, SaddlePoint,
    ShiftSchedule, SparsityPattern, SymmetricLower, Triangle,
};
use nalgebra::{DMatrix, DVector};

/// Sparse copy of a dense matrix: both triangles for symmetric ones, entries with
/// `|a| > 0` plus the diagonal.
fn sparse(a: &DMatrix<f64>) -> SparseColMat<usize, f64> {
    let mut pairs = Vec::new();
    let mut vals = Vec::new();
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            if a[(i, j)] != 0.0 || i == j {
                pairs.push((i, j));
                vals.push(a[(i, j)]);
            }
        }
    }
    SparsityPattern::new(a.nrows(), a.ncols(), &pairs, Triangle::Full)
        .unwrap()
        .assemble(&vals)
        .unwrap()
}

/// Random sparse-ish SPD matrix `B^T B + I` with a banded `B`.
fn random_spd(n: usize, rng: &mut Rng) -> DMatrix<f64> {
    let b = DMatrix::from_fn(n, n, |i, j| {
        if i.abs_diff(j) <= 2 {
            rng.uniform()
        } else {
            0.0
        }
    });
    b.transpose() * &b + DMatrix::identity(n, n)
}

/// Random `m x n` Jacobian with a few entries per row plus a diagonal-like entry (full rank).
fn random_g(m: usize, n: usize, rng: &mut Rng) -> DMatrix<f64> {
    DMatrix::from_fn(m, n, |i, j| {
        if j == 2 * i {
            2.0 + rng.uniform()
        } else if (j + i) % 5 == 0 {
            rng.uniform()
        } else {
            0.0
        }
    })
}

fn kkt_dense(k: &DMatrix<f64>, g: &DMatrix<f64>, c: &DMatrix<f64>) -> DMatrix<f64> {
    let (n, m) = (k.nrows(), g.nrows());
    let mut a = DMatrix::zeros(n + m, n + m);
    a.view_mut((0, 0), (n, n)).copy_from(k);
    a.view_mut((n, 0), (m, n)).copy_from(g);
    a.view_mut((0, n), (n, m)).copy_from(&g.transpose());
    a.view_mut((n, n), (m, m)).copy_from(&(-c));
    a
}

fn dense_solve(a: &DMatrix<f64>, b: &[f64]) -> Vec<f64> {
    a.clone()
        .lu()
        .solve(&DVector::from_column_slice(b))
        .expect("reference matrix is nonsingular")
        .as_slice()
        .to_vec()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn max_abs(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, x| m.max(x.abs()))
}

#[test]
fn cholesky_matches_dense_lu_and_reuses_the_symbolic_factorization() {
    let mut rng = Rng(7);
    let n = 40;
    let k = random_spd(n, &mut rng);
    let b: Vec<f64> = (0..n).map(|_| rng.uniform()).collect();
    let ks = sparse(&k);
    let mut solver = CholeskySolver::new(ks.symbolic()).unwrap();
    solver.factorize(ks.as_ref(), 0.0).unwrap();
    let x = solver.solve(&b).unwrap();
    let want = dense_solve(&k, &b);
    assert!(max_diff(&x, &want) < 1e-10 * max_abs(&want));
    assert!(solver.report().residual < 1e-12);

    // Same pattern, new values: the analysed pattern is reused.
    let k2 = &k * 3.0 + DMatrix::identity(n, n);
    let ks2 = sparse(&k2);
    solver.factorize(ks2.as_ref(), 0.0).unwrap();
    let x2 = solver.solve(&b).unwrap();
    let want2 = dense_solve(&k2, &b);
    assert!(max_diff(&x2, &want2) < 1e-10 * max_abs(&want2));

    // A different pattern is refused.
    let other = sparse(&DMatrix::identity(n, n));
    assert_eq!(
        solver.factorize(other.as_ref(), 0.0),
        Err(LinearError::PatternMismatch { what: "K" })
    );
}

#[test]
fn cholesky_reports_indefinite_k_and_the_shift_schedule_cures_it() {
    let mut rng = Rng(11);
    let n = 20;
    let mut k = random_spd(n, &mut rng);
    k[(5, 5)] -= 100.0;
    let ks = sparse(&k);
    let mut solver = CholeskySolver::new(ks.symbolic()).unwrap();
    assert!(matches!(
        solver.factorize(ks.as_ref(), 0.0),
        Err(LinearError::NotPositiveDefinite { .. })
    ));
    assert!(matches!(
        solver.solve(&[1.0; 20]),
        Err(LinearError::NotFactorized)
    ));
    let schedule = ShiftSchedule {
        initial: 1e-3,
        growth: 10.0,
        max_attempts: 8,
    };
    let shift = solver
        .factorize_with_shifts(ks.as_ref(), &schedule)
        .unwrap();
    assert!(shift > 0.0);
    let b: Vec<f64> = (0..n).map(|_| rng.uniform()).collect();
    let x = solver.solve(&b).unwrap();
    let want = dense_solve(&(k + DMatrix::identity(n, n) * shift), &b);
    assert!(max_diff(&x, &want) < 1e-9 * max_abs(&want));
    assert!(solver.report().factorizations > 1);
}

/// Solves the random KKT system with compliance `c` (zero matrix = `C = 0`) and checks
/// it against dense LU; also the MINRES solution.
fn check_random_kkt(c_scale: f64, seed: u64) {
    let mut rng = Rng(seed);
    let (n, m) = (30, 12);
    let k = random_spd(n, &mut rng);
    let g = random_g(m, n, &mut rng);
    let c = DMatrix::from_fn(m, m, |i, j| {
        if i == j {
            c_scale * (1.0 + rng.uniform().abs())
        } else {
            0.0
        }
    });
    let b: Vec<f64> = (0..n + m).map(|_| rng.uniform()).collect();
    let (ks, gs, cs) = (sparse(&k), sparse(&g), sparse(&c));
    let c_opt = (c_scale > 0.0).then(|| cs.as_ref());
    // Anchor constraint i at DOF 2i (its largest G entry); the last row is free.
    let anchors: Vec<Option<usize>> = (0..m).map(|i| (i + 1 < m).then_some(2 * i)).collect();
    let mut solver = KktSolver::new(
        ks.symbolic(),
        gs.symbolic(),
        c_opt.map(|c| c.symbolic()),
        &anchors,
        KktOptions::default(),
    )
    .unwrap();
    solver
        .factorize(ks.as_ref(), gs.as_ref(), c_opt, 0.0)
        .unwrap();
    let x = solver.solve(&b).unwrap();
    let want = dense_solve(&kkt_dense(&k, &g, &c), &b);
    assert!(
        max_diff(&x, &want) < 1e-10 * max_abs(&want),
        "C scale {c_scale}"
    );
    let report = solver.report().clone();
    assert!(report.residual < 1e-10, "{report:?}");
    let inertia = report.inertia.expect("LDL^T inertia");
    assert_eq!((inertia.positive, inertia.negative), (n, m), "{report:?}");

    // Symbolic reuse: new values on the same pattern give the new solution.
    let k2 = &k * 2.0;
    let g2 = &g * 0.5;
    let ks2 = sparse(&k2);
    let gs2 = sparse(&g2);
    solver
        .factorize(ks2.as_ref(), gs2.as_ref(), c_opt, 0.0)
        .unwrap();
    let x2 = solver.solve(&b).unwrap();
    let want2 = dense_solve(&kkt_dense(&k2, &g2, &c), &b);
    assert!(max_diff(&x2, &want2) < 1e-10 * max_abs(&want2));

    // MINRES with the saddle-point Jacobi preconditioner matches.
    let c_op = c_opt.map(SymmetricLower);
    let op = SaddlePoint {
        k: &SymmetricLower(ks.as_ref()),
        g: gs.as_ref(),
        c: c_op.as_ref().map(|c| c as &dyn LinearOperator),
    };
    let c_diag = c_opt.map(diagonal);
    let pre = Jacobi::from_diagonal(&saddle_point_diagonal(
        &diagonal(ks.as_ref()),
        gs.as_ref(),
        c_diag.as_deref(),
    ));
    let mut y = vec![0.0; n + m];
    let options = IterativeOptions {
        tolerance: 1e-12,
        max_iterations: 500,
    };
    let it = minres(&op, &pre, &b, &mut y, options).unwrap();
    assert!(it.residual <= 1e-12);
    assert!(max_diff(&y, &want) < 1e-8 * max_abs(&want), "{it:?}");
}

#[test]
fn kkt_matches_dense_lu_with_compliance() {
    check_random_kkt(0.1, 3);
}

#[test]
fn kkt_matches_dense_lu_at_zero_compliance() {
    check_random_kkt(0.0, 5);
}

/// A cavity's volume row in a stiff body, scaled as in SI units: `K` of `1e6` (N/m), one
/// dense row `G` of `1e-4` (m^2, the faces' area vectors) and a right-hand side carried by that
/// row alone (a volume increment of `1e-7` m^3). The solution (`p` about `1e5` Pa) is
/// backward stable, but the force rows' rounding, `eps |K| |u|`, is `1e-6` of `|b|`: measured
/// unscaled, the residual refused it (every `volume_ratio` run of the finger failed its first
/// solve so); in the scaled space, where the factor works, it is at rounding level.
#[test]
fn kkt_residual_is_measured_in_the_scaled_space() {
    let mut rng = Rng(17);
    let (n, m) = (30, 1);
    let k = random_spd(n, &mut rng) * 1e6;
    let g = DMatrix::from_fn(m, n, |_, _| 1e-4 * (1.5 + rng.uniform()));
    let mut b = vec![0.0; n + m];
    b[n] = 1e-7;
    let (ks, gs) = (sparse(&k), sparse(&g));
    let mut solver = KktSolver::new(
        ks.symbolic(),
        gs.symbolic(),
        None,
        &[None],
        KktOptions::default(),
    )
    .unwrap();
    solver
        .factorize(ks.as_ref(), gs.as_ref(), None, 0.0)
        .unwrap();
    let x = solver
        .solve(&b)
        .unwrap_or_else(|e| panic!("{e}: {:?}", solver.report()));
    let want = dense_solve(&kkt_dense(&k, &g, &DMatrix::zeros(m, m)), &b);
    assert!(
        max_diff(&x, &want) < 1e-10 * max_abs(&want),
        "{x:?}\n{want:?}"
    );
    let report = solver.report();
    assert!(report.residual < 1e-12, "{report:?}");
    assert_eq!(report.factorization, Factorization::Ldlt, "{report:?}");
}

#[test]
fn kkt_reports_wrong_inertia_for_negative_curvature_in_the_null_space_of_g() {
    // G constrains DOFs 0 and 1; DOF 4 is free of constraints and has K_44 < 0.
    let (n, m) = (6, 2);
    let mut k = DMatrix::<f64>::identity(n, n) * 2.0;
    k[(0, 1)] = 0.5;
    k[(1, 0)] = 0.5;
    let g = DMatrix::from_fn(m, n, |i, j| if i == j { 1.0 } else { 0.0 });
    let gs = sparse(&g);
    let anchors = [Some(0), Some(1)];
    let solve_with = |k: &DMatrix<f64>| {
        let ks = sparse(k);
        let mut s = KktSolver::new(
            ks.symbolic(),
            gs.symbolic(),
            None,
            &anchors,
            KktOptions::default(),
        )
        .unwrap();
        s.factorize(ks.as_ref(), gs.as_ref(), None, 0.0).map(|()| s)
    };
    let mut bad = k.clone();
    bad[(4, 4)] = -1.0;
    match solve_with(&bad) {
        Err(LinearError::WrongInertia { negative, .. }) => assert_eq!(negative, m + 1),
        other => panic!("expected wrong inertia, got {other:?}"),
    }
    // Negative curvature only along the range of G^T is fine: the constraint removes it.
    let mut ok = k.clone();
    ok[(0, 0)] = -1.0;
    ok[(0, 1)] = 0.0;
    ok[(1, 0)] = 0.0;
    let s = solve_with(&ok).unwrap();
    let inertia = s.report().inertia.unwrap();
    assert_eq!((inertia.positive, inertia.negative), (n, m));
    // The shift schedule turns the bad system into a good one.
    let ks = sparse(&bad);
    let mut s = KktSolver::new(
        ks.symbolic(),
        gs.symbolic(),
        None,
        &anchors,
        KktOptions::default(),
    )
    .unwrap();
    let shift = s
        .factorize_with_shifts(
            ks.as_ref(),
            gs.as_ref(),
            None,
            &ShiftSchedule {
                initial: 0.1,
                growth: 4.0,
                max_attempts: 6,
            },
        )
        .unwrap();
    assert!(shift > 1.0);
}

/// `K` of [`P1Box`] assembled.
fn p1_box_k(p: &P1Box) -> SparseColMat<usize, f64> {
    SparsityPattern::new(p.n, p.n, &p.k_pairs, Triangle::Full)
        .unwrap()
        .assemble(&p.k_values)
        .unwrap()
}

/// The C = 0 P1-P1 KKT is singular (spurious pressure modes) but the displacement is
/// unique: a consistent right-hand side `A (u*, p*)` must give back `u*` exactly, with
/// regularized pivots and, without regularization, through the sparse `LU` fallback (which
/// must succeed and agree).
#[test]
fn p1_box_kkt_at_zero_compliance_is_solved_with_regularization_and_refinement() {
    let p = p1_box([12, 4, 4]);
    let (k, g, anchors) = (p1_box_k(&p), p.g, p.anchors);
    let (n, m) = (k.nrows(), g.nrows());
    let mut rng = Rng(13);
    let truth: Vec<f64> = (0..n + m).map(|_| rng.uniform()).collect();
    let op_k = SymmetricLower(k.as_ref());
    let op = SaddlePoint {
        k: &op_k,
        g: g.as_ref(),
        c: None,
    };
    let mut b = vec![0.0; n + m];
    op.apply(&truth, &mut b);

    let mut solver = KktSolver::new(
        k.symbolic(),
        g.symbolic(),
        None,
        &anchors,
        KktOptions::default(),
    )
    .unwrap();
    solver.factorize(k.as_ref(), g.as_ref(), None, 0.0).unwrap();
    let x = solver.solve(&b).unwrap();
    let report = solver.report().clone();
    eprintln!("P1 box n = {n}, m = {m}: {report:?}");
    assert!(x.iter().all(|v| v.is_finite()));
    assert!(report.residual < 1e-12, "{report:?}");
    // Tiny pivots are regularized; the inertia is consistent with K positive definite on
    // the null space of G: at least n positive pivots, at most 3 more (the spurious
    // pressure modes of G^T, perturbed by the regularization).
    assert!(report.regularized_pivots >= 3, "{report:?}");
    let inertia = report.inertia.unwrap();
    assert!(
        inertia.positive >= n && inertia.positive <= n + 3,
        "{report:?}"
    );
    assert_eq!(inertia.positive + inertia.negative, n + m);
    assert!(relative_residual(&op, &x, &b) < 1e-12);
    assert!(
        max_diff(&x[..n], &truth[..n]) < 1e-9 * max_abs(&truth[..n]),
        "displacement differs"
    );

    // The displacement agrees with the sparse LU fallback too: without regularization the
    // zero pivots of the spurious pressure modes send the factorization to LU, which must
    // then factor the singular but consistent system and solve it.
    let mut lu = KktSolver::new(
        k.symbolic(),
        g.symbolic(),
        None,
        &anchors,
        KktOptions {
            pivot_regularization: None,
            ..KktOptions::default()
        },
    )
    .unwrap();
    lu.factorize(k.as_ref(), g.as_ref(), None, 0.0)
        .expect("the LU fallback factors the singular KKT");
    let y = lu
        .solve(&b)
        .expect("the LU fallback solves a consistent system");
    let report = lu.report();
    eprintln!("LU-path report: {report:?}");
    assert_eq!(report.factorization, Factorization::Lu, "{report:?}");
    assert!(report.residual < 1e-12, "{report:?}");
    assert!(max_diff(&x[..n], &y[..n]) < 1e-8 * max_abs(&truth[..n]));

    // Krylov solvers on the same system: CG on K, MINRES on the singular KKT.
    let mut u = vec![0.0; n];
    let it = cg(
        &op_k,
        &Jacobi::from_diagonal(&diagonal(k.as_ref())),
        &b[..n],
        &mut u,
        IterativeOptions {
            tolerance: 1e-12,
            max_iterations: 2000,
        },
    )
    .unwrap();
    let mut chol = CholeskySolver::new(k.symbolic()).unwrap();
    chol.factorize(k.as_ref(), 0.0).unwrap();
    let u_direct = chol.solve(&b[..n]).unwrap();
    assert!(
        max_diff(&u, &u_direct) < 1e-9 * max_abs(&u_direct),
        "CG {it:?}"
    );

    let pre = Jacobi::from_diagonal(&saddle_point_diagonal(
        &diagonal(k.as_ref()),
        g.as_ref(),
        None,
    ));
    let mut y = vec![0.0; n + m];
    let it = minres(
        &op,
        &pre,
        &b,
        &mut y,
        IterativeOptions {
            tolerance: 1e-11,
            max_iterations: 5000,
        },
    )
    .unwrap();
    assert!(
        max_diff(&y[..n], &truth[..n]) < 1e-7 * max_abs(&truth[..n]),
        "MINRES {it:?}"
    );
}

/// Conjugate gradients on an indefinite operator is a breakdown, not a wrong answer;
/// running out of iterations carries the residual.
#[test]
fn krylov_failures_are_error_values() {
    let a = sparse(&DMatrix::from_diagonal(&DVector::from_vec(vec![
        1.0, -1.0, 2.0,
    ])));
    let op = a.as_ref();
    let b = [1.0, 1.0, 1.0];
    let mut x = [0.0; 3];
    let pre = Jacobi::identity(3);
    assert!(matches!(
        cg(
            &op as &dyn LinearOperator,
            &pre,
            &b,
            &mut x,
            IterativeOptions::default()
        ),
        Err(LinearError::Breakdown { .. })
    ));
    let spd = sparse(&random_spd(50, &mut Rng(3)));
    let mut x = vec![0.0; 50];
    let err = cg(
        &SymmetricLower(spd.as_ref()),
        &Jacobi::identity(50),
        &[1.0; 50],
        &mut x,
        IterativeOptions {
            tolerance: 1e-14,
            max_iterations: 2,
        },
    );
    assert!(
        matches!(err, Err(LinearError::NotConverged { iterations: 2, residual, .. }) if residual > 0.0)
    );
    assert!(matches!(
        minres(
            &op as &dyn LinearOperator,
            &pre,
            &[1.0; 2],
            &mut [0.0; 3],
            IterativeOptions::default()
        ),
        Err(LinearError::DimensionMismatch { .. })
    ));
}

/// A right-hand side with a component along the spurious pressure modes has no solution
/// at `C = 0`: the solver says so with an error value instead of returning a huge step.
#[test]
fn p1_box_kkt_with_inconsistent_rhs_is_an_error_value() {
    let p = p1_box([6, 3, 3]);
    let (k, g, anchors) = (p1_box_k(&p), p.g, p.anchors);
    let (n, m) = (k.nrows(), g.nrows());
    let mut rng = Rng(17);
    let b: Vec<f64> = (0..n + m).map(|_| rng.uniform()).collect();
    let mut solver = KktSolver::new(
        k.symbolic(),
        g.symbolic(),
        None,
        &anchors,
        KktOptions::default(),
    )
    .unwrap();
    solver.factorize(k.as_ref(), g.as_ref(), None, 0.0).unwrap();
    let result = solver.solve(&b);
    eprintln!("inconsistent: {result:?} {:?}", solver.report());
    assert!(
        matches!(result, Err(LinearError::InaccurateSolution { .. })),
        "{result:?}"
    );
}
