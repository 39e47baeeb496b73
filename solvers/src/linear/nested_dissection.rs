//! Nested-dissection ordering by METIS (`METIS_NodeND`, multilevel vertex separators with
//! graph compression), called through the raw bindings of `metis-sys`, which builds
//! METIS's vendored C sources.

use super::LinearError;
use faer::sparse::SymbolicSparseColMatRef;
use metis_sys::idx_t;

/// Nested-dissection permutation `(fwd, inv)` (`fwd[new] = old`) of the symmetric graph
/// whose edges are the off-diagonal entries of `graph` (both triangles, or one: the
/// pattern is symmetrized).
pub(crate) fn nested_dissection(
    graph: SymbolicSparseColMatRef<'_, usize>,
) -> Result<(Vec<usize>, Vec<usize>), LinearError> {
    let n = graph.nrows();
    if n == 0 {
        return Ok((Vec::new(), Vec::new()));
    }
    let (mut xadj, mut adjncy) = adjacency(graph)?;
    let mut nvtxs = index(n)?;
    let mut options = [0 as idx_t; metis_sys::METIS_NOPTIONS as usize];
    let mut perm = vec![0 as idx_t; n];
    let mut iperm = vec![0 as idx_t; n];
    // SAFETY: METIS reads `xadj` (n + 1 entries) and `adjncy` (xadj[n] entries, each in
    // 0..n, no self loops, symmetric: built so by `adjacency`), reads `options` (the
    // METIS_NOPTIONS entries it was just given by METIS_SetDefaultOptions) and writes n
    // entries to each of `perm` and `iperm`; `vwgt` may be null. Nothing is kept after the
    // call returns.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        metis_sys::METIS_NodeND(
            &mut nvtxs,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    check(status)?;
    let to_usize = |v: Vec<idx_t>| -> Result<Vec<usize>, LinearError> {
        v.into_iter()
            .map(|i| {
                usize::try_from(i)
                    .ok()
                    .filter(|&i| i < n)
                    .ok_or_else(|| metis_error(format!("returned index {i} outside 0..{n}")))
            })
            .collect()
    };
    Ok((to_usize(perm)?, to_usize(iperm)?))
}

/// METIS's CSR adjacency (`xadj`, `adjncy`): every off-diagonal entry of `graph` in both
/// directions, each neighbour once.
fn adjacency(
    graph: SymbolicSparseColMatRef<'_, usize>,
) -> Result<(Vec<idx_t>, Vec<idx_t>), LinearError> {
    let n = graph.nrows();
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
    for j in 0..graph.ncols() {
        for &i in &graph.row_idx()[graph.col_range(j)] {
            if i != j {
                neighbours[i].push(j);
                neighbours[j].push(i);
            }
        }
    }
    let mut xadj = Vec::with_capacity(n + 1);
    let mut adjncy = Vec::new();
    xadj.push(0);
    for list in &mut neighbours {
        list.sort_unstable();
        list.dedup();
        for &v in list.iter() {
            adjncy.push(index(v)?);
        }
        xadj.push(index(adjncy.len())?);
    }
    Ok((xadj, adjncy))
}

/// `i` as METIS's 32-bit index.
fn index(i: usize) -> Result<idx_t, LinearError> {
    idx_t::try_from(i).map_err(|_| {
        metis_error(format!(
            "index {i} does not fit METIS's 32-bit indices (graph too large)"
        ))
    })
}

/// METIS's return code as a result.
fn check(status: std::os::raw::c_int) -> Result<(), LinearError> {
    match status {
        metis_sys::rstatus_et_METIS_OK => Ok(()),
        metis_sys::rstatus_et_METIS_ERROR_INPUT => Err(metis_error("input error".into())),
        metis_sys::rstatus_et_METIS_ERROR_MEMORY => Err(metis_error("out of memory".into())),
        other => Err(metis_error(format!("error (status {other})"))),
    }
}

fn metis_error(message: String) -> LinearError {
    LinearError::Ordering {
        algorithm: "METIS nested dissection",
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn metis_status_codes_become_errors() {
        assert!(check(metis_sys::rstatus_et_METIS_OK).is_ok());
        for status in [
            metis_sys::rstatus_et_METIS_ERROR_INPUT,
            metis_sys::rstatus_et_METIS_ERROR_MEMORY,
            metis_sys::rstatus_et_METIS_ERROR,
        ] {
            assert!(matches!(check(status), Err(LinearError::Ordering { .. })));
        }
        assert!(matches!(
            index(usize::MAX),
            Err(LinearError::Ordering { .. })
        ));
    }
}
