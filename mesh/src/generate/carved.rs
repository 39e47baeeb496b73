//! Box grids with hexes removed (holes, chambers, gaps), and the named groups of their
//! boundary faces: the construction of the spine arm and the pneumatic actuators. Every tet
//! is a Kuhn tet of a hex of the grid, so the worst tet is that of the flattest hex.

use super::grid::lined_grid_flipped;
use crate::{MeshError, PhysicalGroup, TetMesh};
use std::ops::Range;

/// A hex of the grid by its indices along x, y and z; a neighbour across the grid's outer
/// faces has index -1 or `n` along that axis.
pub(super) type Cell = [isize; 3];

/// A carved grid: the mesh of its kept hexes, and each boundary face with the hex across it.
pub(super) struct Carved {
    /// The kept tets, vertices numbered in order of first use.
    pub mesh: TetMesh,
    /// Outward boundary faces, each with the (removed or outside) hex across it.
    pub faces: Vec<([usize; 3], Cell)>,
}

/// Grid lines along one axis: `segments` of `(length, cells at res 1)` laid end to end from
/// 0, each cut into `res` times its cells of equal size.
pub(super) fn graded_lines(segments: &[(f64, usize)], res: usize) -> Vec<f64> {
    let mut lines = vec![0.0];
    let mut start = 0.0;
    for &(length, cells) in segments {
        let n = cells * res;
        lines.extend((1..=n).map(|i| start + length * (i as f64 / n as f64)));
        start += length;
    }
    lines
}

/// The segment index of every hex along one axis of [`graded_lines`]`(segments, res)`.
pub(super) fn segment_indices(segments: &[(f64, usize)], res: usize) -> Vec<usize> {
    segments
        .iter()
        .enumerate()
        .flat_map(|(s, &(_, n))| std::iter::repeat_n(s, n * res))
        .collect()
}

/// The hex indices of segment `index` of `segments` at `res`.
pub(super) fn segment_cells(segments: &[(f64, usize)], res: usize, index: usize) -> Range<isize> {
    let start: usize = segments[..index].iter().map(|s| s.1 * res).sum();
    start as isize..(start + segments[index].1 * res) as isize
}

/// The grid of `lines` with the hexes where `solid` is false removed; vertices no kept tet
/// uses are dropped. Fails if nothing is kept.
pub(super) fn carve(
    lines: &[Vec<f64>; 3],
    solid: impl Fn(Cell) -> bool,
) -> Result<Carved, MeshError> {
    carve_flipped(lines, |_, _| false, solid)
}

/// [`carve`] with the split of a hex reflected along the axes where `flip(axis, cell index
/// along axis)` holds (see [`super::lattice::Lattice::tets_flipped`]): for grids whose
/// vertices are then mapped onto rounded shapes, whose corner hexes need their diagonal
/// through the corner.
pub(super) fn carve_flipped(
    lines: &[Vec<f64>; 3],
    flip: impl Fn(usize, usize) -> bool,
    solid: impl Fn(Cell) -> bool,
) -> Result<Carved, MeshError> {
    let (grid_positions, grid_tets) = lined_grid_flipped(lines, flip);
    let [nx, ny, _] = [0, 1, 2].map(|a| lines[a].len() - 1);
    let cell_of = |e: usize| {
        let c = e / 6;
        [c % nx, (c / nx) % ny, c / (nx * ny)].map(|i| i as isize)
    };
    let mut index = vec![usize::MAX; grid_positions.len()];
    let mut positions = Vec::new();
    let mut tets = Vec::new();
    let mut cells = Vec::new();
    for (e, t) in grid_tets.iter().enumerate() {
        if !solid(cell_of(e)) {
            continue;
        }
        tets.push(t.map(|v| {
            if index[v] == usize::MAX {
                index[v] = positions.len();
                positions.push(grid_positions[v]);
            }
            index[v]
        }));
        cells.push(cell_of(e));
    }
    let mesh = TetMesh::new(positions, tets)?;
    let surface = mesh.boundary()?;
    let x = mesh.positions();
    let faces = surface
        .triangles()
        .iter()
        .zip(surface.owner_tets())
        .map(|(&[a, b, c], &e)| {
            // A boundary face lies on a face of its hex: its normal is along one axis.
            let normal = (x[b] - x[a]).cross(&(x[c] - x[a]));
            let axis = normal.iamax();
            let mut across = cells[e];
            across[axis] += normal[axis].signum() as isize;
            ([a, b, c], across)
        })
        .collect();
    Ok(Carved { mesh, faces })
}

impl Carved {
    /// The surface group `name` (number `tag`) of the boundary faces whose hex across is
    /// picked by `pick`.
    pub fn group(&self, name: &str, tag: i64, pick: impl Fn(Cell) -> bool) -> PhysicalGroup {
        let faces = self
            .faces
            .iter()
            .filter(|(_, across)| pick(*across))
            .map(|(face, _)| *face)
            .collect();
        PhysicalGroup::surface(name, tag, faces)
    }
}

/// Whether `cell` lies in the box of hex ranges `ranges`.
pub(super) fn within(cell: Cell, ranges: &[Range<isize>; 3]) -> bool {
    (0..3).all(|a| ranges[a].contains(&cell[a]))
}

/// A box of `segments` along x, y and z (`(length, cells at res 1)` each) with one closed
/// chamber: the hexes of the middle segment along every axis removed. Returns the carved box
/// and the chamber's hex ranges.
pub(super) fn chambered_box(
    segments: &[[(f64, usize); 3]; 3],
    res: usize,
) -> Result<(Carved, [Range<isize>; 3]), MeshError> {
    let lines = [0, 1, 2].map(|a| graded_lines(&segments[a], res));
    let chamber = [0, 1, 2].map(|a| segment_cells(&segments[a], res, 1));
    let carved = carve(&lines, |c| !within(c, &chamber))?;
    Ok((carved, chamber))
}
