//! Proptest strategies shared by the test suites: deformation gradients and perturbed meshes,
//! of 4-node tets and of straight or curved 10-node tets.

use nalgebra::{Matrix3, Vector3};
use proptest::prelude::*;

/// Random `F = I + M` with entries of `M` in `[-spread, spread]`.
pub fn near_identity(spread: f64) -> impl Strategy<Value = Matrix3<f64>> {
    proptest::array::uniform9(-spread..spread)
        .prop_map(|m| Matrix3::identity() + Matrix3::from_column_slice(&m))
}

/// Random `F` with `det F` in `[j_min, j_max]`: a random rotation-free shape of unit
/// determinant scaled by `J^(1/3)` with `J` drawn log-uniformly; with `inverted`, one
/// axis is reflected so that `det F = -J`.
pub fn with_determinant(
    j_min: f64,
    j_max: f64,
    inverted: bool,
) -> impl Strategy<Value = Matrix3<f64>> {
    (
        proptest::array::uniform9(-0.4..0.4f64),
        j_min.ln()..j_max.ln(),
    )
        .prop_filter_map("shape matrix must be invertible", move |(m, log_j)| {
            let shape = Matrix3::identity() + Matrix3::from_column_slice(&m);
            let d = shape.determinant();
            if d < 0.2 {
                return None;
            }
            let unit = shape / d.cbrt();
            let mut f = unit * log_j.exp().cbrt();
            if inverted {
                f.column_mut(2).neg_mut();
            }
            Some(f)
        })
}

/// A random, reasonably shaped, positively oriented rest tet: a perturbed regular-ish tet
/// scaled by a factor in `[0.1, 10]` and translated, with `V >= 0.02 l_max^3`.
pub fn rest_tet() -> impl Strategy<Value = [Vector3<f64>; 4]> {
    (
        proptest::array::uniform12(-0.3..0.3f64),
        -1.0..1.0f64,
        proptest::array::uniform3(-5.0..5.0f64),
    )
        .prop_filter_map("rest tet must be well shaped", |(d, log_scale, shift)| {
            let base = [
                Vector3::new(0.0, 0.0, 0.0),
                Vector3::new(1.0, 0.0, 0.0),
                Vector3::new(0.0, 1.0, 0.0),
                Vector3::new(0.0, 0.0, 1.0),
            ];
            let scale = 10f64.powf(log_scale);
            let shift = Vector3::from(shift);
            let x: [Vector3<f64>; 4] = std::array::from_fn(|a| {
                (base[a] + Vector3::new(d[3 * a], d[3 * a + 1], d[3 * a + 2])) * scale + shift
            });
            let v = (x[1] - x[0]).dot(&(x[2] - x[0]).cross(&(x[3] - x[0]))) / 6.0;
            let l = max_edge(&x);
            (v >= 0.02 * l * l * l).then_some(x)
        })
}

/// A random rest triangle in 3D with area `>= 0.1 l_max^2`, sized between 0.1 and 10.
pub fn rest_triangle() -> impl Strategy<Value = [Vector3<f64>; 3]> {
    (proptest::array::uniform9(-1.0..1.0f64), -1.0..1.0f64).prop_filter_map(
        "rest triangle must be well shaped",
        |(d, log_scale)| {
            let scale = 10f64.powf(log_scale);
            let x: [Vector3<f64>; 3] =
                std::array::from_fn(|a| Vector3::new(d[3 * a], d[3 * a + 1], d[3 * a + 2]) * scale);
            let area = 0.5 * (x[1] - x[0]).cross(&(x[2] - x[0])).norm();
            let l = max_edge(&x);
            (area >= 0.1 * l * l).then_some(x)
        },
    )
}

/// Longest edge of a simplex given by its vertices.
pub fn max_edge<const N: usize>(x: &[Vector3<f64>; N]) -> f64 {
    let mut l: f64 = 0.0;
    for a in 0..N {
        for b in a + 1..N {
            l = l.max((x[a] - x[b]).norm());
        }
    }
    l
}

/// A rest mesh and a deformed configuration `x` of its vertices.
#[derive(Debug, Clone)]
pub struct Deformed {
    /// The rest mesh.
    pub mesh: isochor_mesh::TetMesh,
    /// Deformed positions, one per vertex.
    pub x: Vec<isochor_mesh::Vec3>,
}

impl Deformed {
    /// Smallest volume ratio `v_e / V_e` over the tets.
    pub fn min_volume_ratio(&self) -> f64 {
        let rest = self.mesh.rest_volumes();
        (0..self.mesh.num_tets())
            .map(|e| self.mesh.volume_at(e, &self.x) / rest[e])
            .fold(f64::INFINITY, f64::min)
    }
}

/// Random displacements of `n` vertices, each coordinate in `[-amplitude, amplitude]`.
fn displacements(n: usize, amplitude: f64) -> impl Strategy<Value = Vec<isochor_mesh::Vec3>> {
    proptest::collection::vec(
        proptest::array::uniform3(-amplitude..amplitude).prop_map(isochor_mesh::Vec3::from),
        n,
    )
}

/// `mesh` with every vertex displaced by up to `amplitude` per coordinate, keeping only
/// configurations whose smallest volume ratio is at least `j_min`.
fn deform(
    mesh: isochor_mesh::TetMesh,
    amplitude: f64,
    j_min: f64,
) -> impl Strategy<Value = Deformed> {
    displacements(mesh.num_vertices(), amplitude).prop_filter_map(
        "a tet is too compressed or inverted",
        move |u| {
            let x = mesh
                .positions()
                .iter()
                .zip(&u)
                .map(|(p, d)| p + d)
                .collect();
            let deformed = Deformed {
                mesh: mesh.clone(),
                x,
            };
            (deformed.min_volume_ratio() >= j_min).then_some(deformed)
        },
    )
}

/// Two tets sharing the face `(0, 1, 2)` (apexes 3 above and 4 below), rest vertices
/// jittered by up to `rest_jitter` per coordinate around a unit-size reference, deformed by
/// up to `amplitude` per coordinate, with every volume ratio at least `j_min`.
pub fn two_tets(rest_jitter: f64, amplitude: f64, j_min: f64) -> impl Strategy<Value = Deformed> {
    let reference = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.3, 0.3, 1.0],
        [0.2, 0.3, -0.8],
    ];
    displacements(5, rest_jitter)
        .prop_filter_map("jittered rest mesh must be valid", move |jitter| {
            let positions = reference
                .iter()
                .zip(&jitter)
                .map(|(p, d)| isochor_mesh::Vec3::from(*p) + d)
                .collect();
            isochor_mesh::TetMesh::new(positions, vec![[0, 1, 2, 3], [0, 2, 1, 4]]).ok()
        })
        .prop_flat_map(move |mesh| deform(mesh, amplitude, j_min))
}

/// The unit cube split by [`isochor_mesh::generate::box_grid`] into `cells`, deformed by up
/// to `amplitude` per coordinate, with every volume ratio at least `j_min`.
pub fn deformed_box(
    cells: [usize; 3],
    amplitude: f64,
    j_min: f64,
) -> impl Strategy<Value = Deformed> {
    let mesh = isochor_mesh::generate::box_grid(
        isochor_mesh::Vec3::zeros(),
        isochor_mesh::Vec3::repeat(1.0),
        cells,
    )
    .ok();
    proptest::strategy::Just(mesh)
        .prop_filter_map("box cells must be valid", |mesh| mesh)
        .prop_flat_map(move |mesh| deform(mesh, amplitude, j_min))
}

/// A mesh of 4- or 10-node tets and positions of all its nodes.
#[derive(Debug, Clone)]
pub struct DeformedElements {
    /// The rest mesh.
    pub mesh: isochor_mesh::ElementMesh,
    /// Deformed positions, one per node.
    pub x: Vec<isochor_mesh::Vec3>,
}

/// The volume ratios `det F` at the points of every quadrature rule in every element of
/// `mesh` with node positions `x`.
pub fn volume_ratios(mesh: &isochor_mesh::ElementMesh, x: &[isochor_mesh::Vec3]) -> Vec<f64> {
    use isochor_mesh::element::{deformation_gradient, TetQuadrature};
    let mut ratios = Vec::new();
    for rule in TetQuadrature::ALL {
        let geometry = mesh.rest_geometry(rule).expect("rest geometry");
        for e in 0..mesh.num_elements() {
            for q in 0..rule.num_points() {
                let f = deformation_gradient(x, mesh.element(e), geometry.gradients(e, q));
                ratios.push(f.determinant());
            }
        }
    }
    ratios
}

/// `mesh` with its mid-edge nodes moved by `offsets[i] * scale` (node `num_vertices + i`),
/// rebuilt through [`isochor_mesh::ElementMesh::from_nodes`] (which rejects folded elements);
/// `None` unless `det(dX/dxi)` stays within a factor 4 in every element at the points of the
/// degree-5 rule (a curved element, but not a nearly folded one).
fn bend(
    mesh: &isochor_mesh::ElementMesh,
    offsets: &[isochor_mesh::Vec3],
    scale: f64,
) -> Option<isochor_mesh::ElementMesh> {
    use isochor_mesh::element::TetQuadrature;
    let nv = mesh.num_vertices();
    let mut nodes = mesh.nodes().to_vec();
    for (node, d) in nodes[nv..].iter_mut().zip(offsets) {
        *node += d * scale;
    }
    let bent =
        isochor_mesh::ElementMesh::from_nodes(mesh.kind(), nodes, mesh.connectivity().to_vec())
            .ok()?;
    let rule = TetQuadrature::Degree5;
    let geometry = bent.rest_geometry(rule).ok()?;
    (0..bent.num_elements())
        .all(|e| {
            let dets = geometry
                .element_weights(e)
                .iter()
                .zip(rule.weights())
                .map(|(w, r)| w / r);
            let (lo, hi) = dets.fold((f64::INFINITY, 0.0f64), |(lo, hi), d| {
                (lo.min(d), hi.max(d))
            });
            lo >= 0.25 * hi
        })
        .then_some(bent)
}

/// A random 10-node tet: the corners of a [`rest_tet`] and its mid-edge nodes, at the edge
/// midpoints moved by up to `curvature` times the longest edge per coordinate (`0` for a
/// straight element), kept when it is well shaped (see the filter of [`quadratic`]).
pub fn rest_tet10(curvature: f64) -> impl Strategy<Value = isochor_mesh::ElementMesh> {
    (rest_tet(), proptest::array::uniform18(-1.0..1.0f64)).prop_filter_map(
        "curved element must stay well shaped",
        move |(corners, d)| {
            let mesh = isochor_mesh::TetMesh::new(corners.to_vec(), vec![[0, 1, 2, 3]]).ok()?;
            let offsets: Vec<Vector3<f64>> =
                d.chunks_exact(3).map(Vector3::from_column_slice).collect();
            let straight = isochor_mesh::ElementMesh::quadratic(mesh);
            bend(&straight, &offsets, curvature * max_edge(&corners))
        },
    )
}

/// Positions `F_0 X + noise` of the nodes of `mesh` (noise up to `amplitude` times the
/// deformed size `|det F_0|^(1/3) l` per coordinate, `l` the longest edge of an element's
/// corners, independently per node, so the deformation is not affine on 10-node tets), kept
/// when every volume ratio of [`volume_ratios`] passes `accept`.
pub fn deform_nodes(
    mesh: isochor_mesh::ElementMesh,
    f0: impl Strategy<Value = Matrix3<f64>>,
    amplitude: f64,
    accept: fn(f64) -> bool,
) -> impl Strategy<Value = DeformedElements> {
    let l = longest_edge(mesh.corners());
    let n = mesh.num_nodes();
    (f0, displacements(n, 1.0)).prop_filter_map("a volume ratio is out of range", move |(f0, u)| {
        let x: Vec<_> = mesh
            .nodes()
            .iter()
            .zip(&u)
            .map(|(p, d)| f0 * p + d * (amplitude * l * f0.determinant().abs().cbrt()))
            .collect();
        volume_ratios(&mesh, &x)
            .into_iter()
            .all(accept)
            .then(|| DeformedElements {
                mesh: mesh.clone(),
                x,
            })
    })
}

/// The meshes of `deformed` promoted to 10-node tets: rest mid-edge nodes at the edge
/// midpoints moved by up to `curvature` times the longest edge per coordinate (`0` for straight
/// edges), deformed mid-edge nodes at the midpoints of the deformed corners moved by up to
/// `amplitude` times the longest edge; kept when the rest elements are well shaped
/// (`det(dX/dxi)` within a factor 4 over each element) and every volume ratio is at least
/// `j_min`.
pub fn quadratic(
    deformed: impl Strategy<Value = Deformed>,
    curvature: f64,
    amplitude: f64,
    j_min: f64,
) -> impl Strategy<Value = DeformedElements> {
    deformed.prop_flat_map(move |d| {
        let straight = isochor_mesh::ElementMesh::quadratic(d.mesh.clone());
        let mids = straight.num_nodes() - straight.num_vertices();
        let l = longest_edge(straight.corners());
        (displacements(mids, 1.0), displacements(mids, 1.0)).prop_filter_map(
            "promoted mesh must be valid",
            move |(bends, moves)| {
                let mesh = bend(&straight, &bends, curvature * l)?;
                let mut x = d.x.clone();
                x.extend(
                    mesh.mid_edges()
                        .iter()
                        .zip(&moves)
                        .map(|(&[a, b], m)| 0.5 * (d.x[a] + d.x[b]) + m * (amplitude * l)),
                );
                volume_ratios(&mesh, &x)
                    .iter()
                    .all(|&j| j >= j_min)
                    .then_some(DeformedElements { mesh, x })
            },
        )
    })
}

/// The longest tet edge of `mesh`.
fn longest_edge(mesh: &isochor_mesh::TetMesh) -> f64 {
    mesh.tets()
        .iter()
        .map(|t| max_edge(&t.map(|v| mesh.positions()[v])))
        .fold(0.0, f64::max)
}

/// Material parameters drawn for the derivative tests: shear modulus, Lame's first
/// parameter, the `beta` of `U(J; beta)` (Sheen et al. 2021, eq. 13), the F-bar
/// extension's `epsilon` (eq. 10-12), and the shape of the invariant models relative to `mu`
/// (Mooney-Rivlin's `c01 / c10`, Yeoh's `c20 / c10` and `c30 / c10`).
#[derive(Debug, Clone, Copy)]
pub struct MaterialParams {
    /// Shear modulus `mu` in `[0.1, 10]`.
    pub mu: f64,
    /// Lame's first parameter in `[0.05, 200]`: from compressible to nearly incompressible.
    pub lambda: f64,
    /// `beta` in `[0, 20]`.
    pub beta: f64,
    /// `epsilon` in `[0.01, 0.5]`.
    pub epsilon: f64,
    /// Mooney-Rivlin `c01 / c10` in `[0, 1]` (fits of rubber give 0 to about 0.5).
    pub c01_ratio: f64,
    /// Yeoh `c20 / c10` in `[-0.2, 0.2]` (fits of filled rubber give about -0.05).
    pub c20_ratio: f64,
    /// Yeoh `c30 / c10` in `[0, 0.05]` (fits of filled rubber give about 0.003).
    pub c30_ratio: f64,
}

impl MaterialParams {
    /// Mooney-Rivlin `(c10, c01)` with initial shear modulus `2 (c10 + c01) = mu`.
    pub fn mooney_rivlin(&self) -> (f64, f64) {
        let c10 = 0.5 * self.mu / (1.0 + self.c01_ratio);
        (c10, self.c01_ratio * c10)
    }

    /// Ogden terms `(mu_p, alpha_p)`: the three-term fit of Treloar's data by Ogden 1972
    /// (`alpha = 1.3, 5, -2`), scaled to the initial shear modulus `1/2 sum mu_p alpha_p = mu`.
    pub fn ogden(&self) -> [(f64, f64); 3] {
        let fit = [(0.63, 1.3), (0.0012, 5.0), (-0.01, -2.0)];
        let mu0 = 0.5 * fit.iter().map(|(m, a)| m * a).sum::<f64>();
        fit.map(|(m, a)| (m * self.mu / mu0, a))
    }

    /// Yeoh `(c10, c20, c30)` with initial shear modulus `2 c10 = mu`.
    pub fn yeoh(&self) -> (f64, f64, f64) {
        let c10 = 0.5 * self.mu;
        (c10, self.c20_ratio * c10, self.c30_ratio * c10)
    }
}

/// Random [`MaterialParams`] over the ranges documented on its fields.
pub fn material_params() -> impl Strategy<Value = MaterialParams> {
    (
        (0.1..10.0f64, 0.05..200.0f64, 0.0..20.0f64, 0.01..0.5f64),
        (0.0..1.0f64, -0.2..0.2f64, 0.0..0.05f64),
    )
        .prop_map(
            |((mu, lambda, beta, epsilon), (c01_ratio, c20_ratio, c30_ratio))| MaterialParams {
                mu,
                lambda,
                beta,
                epsilon,
                c01_ratio,
                c20_ratio,
                c30_ratio,
            },
        )
}
