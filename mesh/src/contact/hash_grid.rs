//! Overlapping pairs of boxes by a uniform spatial hash: every box is entered in the grid
//! cells it covers, and a pair is tested only where both share a cell (and reported only in
//! the cell holding the lower corner of their intersection, so once). With cells about twice
//! the mean box size, time and memory grow linearly with the number of boxes for surfaces
//! of even resolution (no all-pairs list).

use super::aabb::Aabb;

/// A grid cell's integer coordinates.
type Cell = [i64; 3];

/// The pairs `[i, j]` of boxes `a[i]`, `b[j]` that overlap, sorted; with `b = None` the
/// pairs `i < j` of `a` with itself.
pub(crate) fn overlapping_pairs(a: &[Aabb], b: Option<&[Aabb]>) -> Vec<[usize; 2]> {
    let second = b.unwrap_or(a);
    let all = || a.iter().chain(b.unwrap_or(&[]));
    let count = a.len() + b.map_or(0, <[Aabb]>::len);
    if a.is_empty() || second.is_empty() {
        return Vec::new();
    }
    let (sum, largest) = all().fold((0.0, 0.0_f64), |(s, m), x| {
        let l = x.longest_side();
        (s + l, m.max(l))
    });
    // Twice the mean size, and large enough that no box covers more than 9^3 cells.
    let mut size = (2.0 * sum / count as f64).max(largest / 8.0);
    if !(size.is_finite() && size > 0.0) {
        size = 1.0;
    }
    let cell_of =
        |p: &crate::Vec3| -> Cell { std::array::from_fn(|k| (p[k] / size).floor() as i64) };
    // (cell, which set, index)
    let mut entries: Vec<(Cell, bool, usize)> = Vec::with_capacity(8 * count);
    let mut enter = |boxes: &[Aabb], set: bool| {
        for (i, x) in boxes.iter().enumerate() {
            let (lo, hi) = (cell_of(&x.min), cell_of(&x.max));
            for cx in lo[0]..=hi[0] {
                for cy in lo[1]..=hi[1] {
                    for cz in lo[2]..=hi[2] {
                        entries.push(([cx, cy, cz], set, i));
                    }
                }
            }
        }
    };
    enter(a, false);
    if let Some(b) = b {
        enter(b, true);
    }
    entries.sort_unstable();
    let mut pairs = Vec::new();
    for run in entries.chunk_by(|x, y| x.0 == y.0) {
        let cell = run[0].0;
        let split = run.partition_point(|e| !e.1);
        let (first, rest) = if b.is_some() {
            (&run[..split], &run[split..])
        } else {
            (run, run)
        };
        for (ei, &(_, _, i)) in first.iter().enumerate() {
            // With one set, each unordered pair once: j after i in the run.
            let others = if b.is_some() { rest } else { &rest[ei + 1..] };
            for &(_, _, j) in others {
                let (x, y) = (&a[i], &second[j]);
                if x.overlaps(y) && cell_of(&x.min.sup(&y.min)) == cell {
                    pairs.push(if b.is_none() && j < i { [j, i] } else { [i, j] });
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs
}
