//! Structured lattices of hexes split into tets (Kuhn's split), with optional mirrored halves
//! and periodic axes: the common topology of every generator.

/// The six tets of the unit hex that share its diagonal from corner `(0,0,0)` to `(1,1,1)`
/// (Kuhn's split). Corners are numbered `i + 2 j + 4 k`. Using the same split in every hex
/// makes the mesh conforming: neighbouring hexes split their shared face along the same
/// diagonal. Each tet is positively oriented.
const KUHN: [[usize; 4]; 6] = [
    [0, 1, 3, 7],
    [0, 3, 2, 7],
    [0, 2, 6, 7],
    [0, 6, 4, 7],
    [0, 4, 5, 7],
    [0, 5, 1, 7],
];

/// A lattice of `cells[0] x cells[1] x cells[2]` hexes.
///
/// Along a `periodic` axis the last layer of hexes wraps around to the first vertex layer
/// (needs at least 3 cells). Along an axis with `mirror = Some(m)`, the hexes below cell
/// index `m` use the Kuhn split reflected about the plane of vertex layer `m`; reflection
/// keeps shared faces conforming and lets the split diagonal point away from the centre in
/// every half, so that mapped corners (square-to-disk, cube-to-ball) never carry a flat tet.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Lattice {
    pub cells: [usize; 3],
    pub periodic: [bool; 3],
    pub mirror: [Option<usize>; 3],
}

impl Lattice {
    /// Vertex layers along `axis`.
    pub fn points_along(&self, axis: usize) -> usize {
        self.cells[axis] + usize::from(!self.periodic[axis])
    }

    /// Number of vertices.
    pub fn num_points(&self) -> usize {
        (0..3).map(|a| self.points_along(a)).product()
    }

    /// Vertex index of lattice point `p` (wrapped along periodic axes): `i + ni (j + nj k)`.
    pub fn index(&self, p: [usize; 3]) -> usize {
        let n = [0, 1, 2].map(|a| self.points_along(a));
        let w = [0, 1, 2].map(|a| if self.periodic[a] { p[a] % n[a] } else { p[a] });
        w[0] + n[0] * (w[1] + n[1] * w[2])
    }

    /// Lattice coordinates of every vertex, in index order.
    pub fn points(&self) -> Vec<[usize; 3]> {
        let n = [0, 1, 2].map(|a| self.points_along(a));
        let mut points = Vec::with_capacity(self.num_points());
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    points.push([i, j, k]);
                }
            }
        }
        points
    }

    /// The tets, six per hex, positively oriented in lattice coordinates.
    pub fn tets(&self) -> Vec<[usize; 4]> {
        self.tets_flipped(|axis, index| self.mirror[axis].is_some_and(|m| index < m))
    }

    /// The tets with the Kuhn split of every hex reflected along the axes where
    /// `flip(axis, cell index along axis)` holds. A reflection along an axis never changes the
    /// split of the faces normal to that axis, so any rule of this form keeps the mesh
    /// conforming; [`Lattice::tets`] flips the hexes below each mirror.
    pub fn tets_flipped(&self, flip: impl Fn(usize, usize) -> bool) -> Vec<[usize; 4]> {
        let [nx, ny, nz] = self.cells;
        let mut tets = Vec::with_capacity(6 * nx * ny * nz);
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let cell = [i, j, k];
                    let flip = [0, 1, 2].map(|a| flip(a, cell[a]));
                    let corner = |c: usize| {
                        self.index([0, 1, 2].map(|a| {
                            let bit = (c >> a) & 1;
                            cell[a] + if flip[a] { 1 - bit } else { bit }
                        }))
                    };
                    let odd = flip.iter().filter(|&&f| f).count() % 2 == 1;
                    tets.extend(KUHN.iter().map(|t| {
                        let mut t = t.map(corner);
                        if odd {
                            t.swap(2, 3);
                        }
                        t
                    }));
                }
            }
        }
        tets
    }
}
