//! Structured box grid split into tets.

use super::lattice::Lattice;
use crate::{MeshError, TetMesh, Vec3};

/// A box `[min, max]` with `cells = [nx, ny, nz]` hexes, each split into the 6 tets that
/// share its diagonal from corner `(i, j, k)` to `(i+1, j+1, k+1)` (Kuhn's split):
/// `6 nx ny nz` tets.
///
/// Vertex `(i, j, k)` has index `i + (nx + 1) * (j + (ny + 1) * k)`.
///
/// ```
/// use isochor_mesh::generate::box_grid;
/// use isochor_mesh::{ElementMesh, Vec3};
///
/// let mesh = box_grid(Vec3::zeros(), Vec3::new(0.1, 0.02, 0.02), [5, 1, 1])?;
/// assert_eq!((mesh.num_vertices(), mesh.num_tets()), (24, 30));
/// assert!((mesh.rest_volume() - 4e-5).abs() < 1e-15);
/// // The same box of 10-node tets (mid-edge nodes added).
/// let quadratic = ElementMesh::quadratic(mesh);
/// assert_eq!(quadratic.num_vertices(), 24);
/// assert_eq!(quadratic.element(0).len(), 10);
/// # Ok::<(), isochor_mesh::MeshError>(())
/// ```
pub fn box_grid(min: Vec3, max: Vec3, cells: [usize; 3]) -> Result<TetMesh, MeshError> {
    let names = ["nx", "ny", "nz"];
    for (axis, &n) in cells.iter().enumerate() {
        if n == 0 {
            return Err(MeshError::parameter(
                names[axis],
                n,
                "at least one cell is needed",
            ));
        }
        if !(min[axis].is_finite() && max[axis].is_finite() && max[axis] > min[axis]) {
            return Err(MeshError::parameter(
                "box",
                format!("[{}, {}]", min[axis], max[axis]),
                format!("axis {axis} must have finite bounds with max > min"),
            ));
        }
    }
    let lines = [0, 1, 2].map(|a| {
        (0..=cells[a])
            .map(|i| min[a] + (max[a] - min[a]) * (i as f64 / cells[a] as f64))
            .collect::<Vec<f64>>()
    });
    let (positions, tets) = lined_grid(&lines);
    TetMesh::new(positions, tets)
}

/// The vertices and tets of the grid whose hexes lie between consecutive `lines` along each
/// axis (increasing, at least two per axis), split as [`box_grid`]'s: vertex `(i, j, k)` is
/// `(lines[0][i], lines[1][j], lines[2][k])`, and hex `c = i + nx (j + ny k)` holds tets
/// `6 c .. 6 c + 6`.
pub(super) fn lined_grid(lines: &[Vec<f64>; 3]) -> (Vec<Vec3>, Vec<[usize; 4]>) {
    lined_grid_flipped(lines, |_, _| false)
}

/// [`lined_grid`] with the split of a hex reflected along the axes where `flip(axis, cell
/// index along axis)` holds ([`Lattice::tets_flipped`]).
pub(super) fn lined_grid_flipped(
    lines: &[Vec<f64>; 3],
    flip: impl Fn(usize, usize) -> bool,
) -> (Vec<Vec3>, Vec<[usize; 4]>) {
    let lattice = Lattice {
        cells: [0, 1, 2].map(|a| lines[a].len() - 1),
        periodic: [false; 3],
        mirror: [None; 3],
    };
    let positions = lattice
        .points()
        .into_iter()
        .map(|[i, j, k]| Vec3::new(lines[0][i], lines[1][j], lines[2][k]))
        .collect();
    (positions, lattice.tets_flipped(flip))
}

/// The vertex and tet counts of [`box_grid`] with `cells` per axis, without generating it
/// (in `f64`, so that a scene's product of cells and resolution cannot wrap).
pub fn box_grid_counts(cells: [f64; 3]) -> (f64, f64) {
    let vertices = cells.iter().map(|c| c + 1.0).product();
    (vertices, 6.0 * cells.iter().product::<f64>())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_volume_is_exact_and_tets_positive() {
        let mesh = box_grid(Vec3::zeros(), Vec3::new(0.2, 0.05, 0.05), [8, 2, 2]).unwrap();
        assert_eq!(mesh.reoriented(), 0);
        assert_eq!(mesh.num_tets(), 6 * 32);
        assert_eq!(mesh.num_vertices(), 9 * 3 * 3);
        let exact = 0.2 * 0.05 * 0.05;
        assert!((mesh.rest_volume() - exact).abs() < 1e-15 * exact * 100.0);
        assert_eq!(
            mesh.positions()[1 + 9 * (2 + 3)],
            Vec3::new(0.025, 0.05, 0.025)
        );
    }

    #[test]
    fn zero_cells_is_an_error() {
        assert!(box_grid(Vec3::zeros(), Vec3::repeat(1.0), [0, 1, 1]).is_err());
        assert!(box_grid(Vec3::zeros(), Vec3::new(1.0, 0.0, 1.0), [1, 1, 1]).is_err());
    }
}
