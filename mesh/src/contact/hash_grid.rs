//! Overlapping pairs of boxes by a uniform spatial hash: every box is entered in the grid
//! cells it covers, and a pair is tested only where both share a cell (and reported only in
//! the cell holding the lower corner of their intersection, so once). With cells about twice
//! the mean box size, time and memory grow linearly with the number of boxes for surfaces
//! of even resolution (no all-pairs list).

use super::aabb::Aabb;
use rayon::slice::ParallelSliceMut;

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
    // A cell's key: its integer coordinates mixed into 64 bits. Two cells with one key only
    // cost extra box tests (and duplicates, removed at the end); no pair is missed.
    let key_of = |p: &crate::Vec3| -> u64 {
        let c: [i64; 3] = std::array::from_fn(|k| (p[k] / size).floor() as i64);
        cell_key(c)
    };
    // (key, index with the set in the top bit), 16 bytes an entry.
    const SECOND: usize = 1 << (usize::BITS - 1);
    let mut entries: Vec<(u64, usize)> = Vec::with_capacity(8 * count);
    let mut enter = |boxes: &[Aabb], set: usize| {
        for (i, x) in boxes.iter().enumerate() {
            let lo: [i64; 3] = std::array::from_fn(|k| (x.min[k] / size).floor() as i64);
            let hi: [i64; 3] = std::array::from_fn(|k| (x.max[k] / size).floor() as i64);
            for cx in lo[0]..=hi[0] {
                for cy in lo[1]..=hi[1] {
                    for cz in lo[2]..=hi[2] {
                        entries.push((cell_key([cx, cy, cz]), i | set));
                    }
                }
            }
        }
    };
    enter(a, 0);
    if let Some(b) = b {
        enter(b, SECOND);
    }
    entries.par_sort_unstable();
    let mut pairs = Vec::new();
    for run in entries.chunk_by(|x, y| x.0 == y.0) {
        let key = run[0].0;
        let split = run.partition_point(|e| e.1 & SECOND == 0);
        let (first, rest) = if b.is_some() {
            (&run[..split], &run[split..])
        } else {
            (run, run)
        };
        for (ei, &(_, i)) in first.iter().enumerate() {
            // With one set, each unordered pair once: j after i in the run.
            let others = if b.is_some() { rest } else { &rest[ei + 1..] };
            for &(_, j) in others {
                let j = j & !SECOND;
                let (x, y) = (&a[i], &second[j]);
                if x.overlaps(y) && key_of(&x.min.sup(&y.min)) == key {
                    pairs.push(if b.is_none() && j < i { [j, i] } else { [i, j] });
                }
            }
        }
    }
    pairs.par_sort_unstable();
    pairs.dedup();
    pairs
}

/// Mixes a cell's coordinates into a key (multiplications by odd constants, as in
/// Teschner et al. 2003, "Optimized Spatial Hashing for Collision Detection of Deformable
/// Objects").
fn cell_key(c: [i64; 3]) -> u64 {
    (c[0] as u64).wrapping_mul(73_856_093)
        ^ (c[1] as u64).wrapping_mul(19_349_663)
        ^ (c[2] as u64).wrapping_mul(83_492_791)
}
