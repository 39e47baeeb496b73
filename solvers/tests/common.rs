//! Problems shared by the solver tests.

#![allow(dead_code)]

use faer::sparse::SparseColMat;
use isochor_mesh::element::ElementMesh;
use isochor_mesh::{generate::box_grid, TetMesh, Vec3};
use isochor_solvers::linear::{SparsityPattern, Triangle};
use isochor_solvers::{Dirichlet, Load, Material, Method, Motion, Problem, RunSummary};
use nalgebra::Matrix3;
use std::time::Duration;

/// Vertices of `mesh` with `coordinate[axis] == value` (to rounding).
pub fn plane(mesh: &TetMesh, axis: usize, value: f64) -> Vec<usize> {
    (0..mesh.num_vertices())
        .filter(|&v| (mesh.positions()[v][axis] - value).abs() < 1e-9)
        .collect()
}

/// The cantilever of the locking study: 0.2 x 0.05 x 0.05 m, `4 res x res x res` cells,
/// clamped at x = 0, under gravity.
pub fn cantilever(res: usize, method: Method, nu: f64) -> Problem {
    beam([4 * res, res, res], method, nu, Vec3::new(0.2, 0.05, 0.05))
}

/// A beam `[0, size]` with `cells`, clamped at x = 0, under gravity.
pub fn beam(cells: [usize; 3], method: Method, nu: f64, size: Vec3) -> Problem {
    let mesh = box_grid(Vec3::zeros(), size, cells).unwrap();
    let clamped = plane(&mesh, 0, 0.0);
    Problem {
        mesh: mesh.into(),
        method,
        material: Material::from_young_poisson(266e3, nu, 1070.0).unwrap(),
        regions: Vec::new(),
        zones: None,
        dirichlet: vec![Dirichlet {
            nodes: clamped,
            axes: [true; 3],
            motion: Motion::Fixed,
            curve: None,
        }],
        loads: vec![Load::Gravity(Vec3::new(0.0, -9.8, 0.0)).into()],
        obstacles: Vec::new(),
        cloths: Vec::new(),
    }
}

/// The cantilever of [`cantilever`] on 10-node tets: the same box grid promoted to quadratic
/// tets, every node of the face `x = 0` (corners and mid-edge nodes) clamped. This is the
/// `cantilever` scene with `element = "tet10"`.
pub fn cantilever_tet10(res: usize, method: Method, nu: f64) -> Problem {
    let mut problem = cantilever(res, method, nu);
    let mesh = ElementMesh::quadratic(problem.mesh.into_corners());
    problem.dirichlet[0].nodes = (0..mesh.num_nodes())
        .filter(|&v| mesh.nodes()[v].x.abs() < 1e-9)
        .collect();
    problem.mesh = mesh;
    problem
}

/// Mean `-u_y` over the free end face `x = length`.
pub fn end_deflection(mesh: &TetMesh, x: &[Vec3]) -> f64 {
    let length = mesh.bounding_box().1.x;
    let end = plane(mesh, 0, length);
    end.iter()
        .map(|&v| mesh.positions()[v].y - x[v].y)
        .sum::<f64>()
        / end.len() as f64
}

/// A P1-P1 saddle point on a Kuhn box grid `[0, 4] x [0, 1]^2`, face `x = 0` clamped: the
/// element-stiffness triplets of a linear-elasticity-like operator (`grad_a . grad_b I +
/// grad_a grad_b^T`, full 3x3 blocks as for real materials), the nodal volume Jacobian `G`
/// (eq. 26-27) and anchors at each node's last free DOF.
pub struct P1Box {
    pub n: usize,
    pub m: usize,
    pub k_pairs: Vec<(usize, usize)>,
    pub k_values: Vec<f64>,
    pub g: SparseColMat<usize, f64>,
    pub anchors: Vec<Option<usize>>,
}

pub fn p1_box(cells: [usize; 3]) -> P1Box {
    let mesh = box_grid(Vec3::zeros(), Vec3::new(4.0, 1.0, 1.0), cells).expect("box");
    let x = mesh.positions();
    let nv = x.len();
    let mut dof = vec![None; 3 * nv];
    let mut n = 0;
    for (v, p) in x.iter().enumerate() {
        if p.x > 1e-12 {
            for a in 0..3 {
                dof[3 * v + a] = Some(n);
                n += 1;
            }
        }
    }
    let (mut k_pairs, mut k_values, mut gp, mut gv) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for tet in mesh.tets() {
        let xs = tet.map(|v| x[v]);
        let e = [xs[1] - xs[0], xs[2] - xs[0], xs[3] - xs[0]];
        let d = Matrix3::from_columns(&e);
        let inv = d.try_inverse().expect("non-degenerate tet");
        let vol = d.determinant().abs() / 6.0;
        let (g1, g2, g3) = (
            inv.row(0).transpose(),
            inv.row(1).transpose(),
            inv.row(2).transpose(),
        );
        let grads = [-(g1 + g2 + g3), g1, g2, g3];
        let v1 = e[1].cross(&e[2]) / 6.0;
        let v2 = e[2].cross(&e[0]) / 6.0;
        let v3 = e[0].cross(&e[1]) / 6.0;
        let vgrad = [-(v1 + v2 + v3), v1, v2, v3];
        for a in 0..4 {
            for b in 0..4 {
                for j in 0..3 {
                    let Some(col) = dof[3 * tet[b] + j] else {
                        continue;
                    };
                    gp.push((tet[a], col));
                    gv.push(0.25 * vgrad[b][j]);
                    for i in 0..3 {
                        if let Some(row) = dof[3 * tet[a] + i] {
                            let lap = if i == j { grads[a].dot(&grads[b]) } else { 0.0 };
                            k_pairs.push((row, col));
                            k_values.push(vol * (lap + grads[a][i] * grads[b][j]));
                        }
                    }
                }
            }
        }
    }
    let g = SparsityPattern::new(nv, n, &gp, Triangle::Full)
        .and_then(|p| p.assemble(&gv))
        .expect("G");
    let anchors = (0..nv).map(|v| dof[3 * v + 2]).collect();
    P1Box {
        n,
        m: nv,
        k_pairs,
        k_values,
        g,
        anchors,
    }
}

/// Per-iteration means of the solver's own timings over a run: assembly, factorization,
/// solve, and the whole step.
pub fn per_iteration(summary: &RunSummary) -> [Duration; 4] {
    let n = summary.newton_iterations().max(1) as u32;
    let mut t = [Duration::ZERO; 4];
    for r in &summary.reports {
        t[0] += r.timings.assembly;
        t[1] += r.timings.factorization;
        t[2] += r.timings.solve;
        t[3] += r.wall_time;
    }
    t.map(|d| d / n)
}

/// Largest displacement difference relative to the largest displacement.
pub fn relative_difference(rest: &[Vec3], a: &[Vec3], b: &[Vec3]) -> f64 {
    let scale = rest
        .iter()
        .zip(a)
        .map(|(r, x)| (x - r).norm())
        .fold(0.0, f64::max);
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, f64::max);
    diff / scale
}

/// Deterministic pseudo-random numbers in [-1, 1) (xorshift).
pub struct Rng(pub u64);

impl Rng {
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// The comma-separated list of the environment variable `key` (else `default`), parsed: how
/// the ignored studies take their resolutions and cases.
#[allow(dead_code)]
pub fn study_list<T: std::str::FromStr>(key: &str, default: &str) -> Vec<T> {
    std::env::var(key)
        .unwrap_or_else(|_| default.into())
        .split(',')
        .map(|item| {
            item.trim()
                .parse()
                .unwrap_or_else(|_| panic!("{key}: cannot parse '{item}'"))
        })
        .collect()
}
