//! Atomic file writes: write a temporary file in the target's directory, then rename it over
//! the target, so a reader (ParaView watching a series) never sees a half-written file.

use crate::MeshError;
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// Writes `path` through `write`, atomically. On failure the temporary file is removed and
/// the target is left as it was.
pub(crate) fn write_atomic(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<(), MeshError> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path.file_name().ok_or_else(|| MeshError::Format {
        path: path.into(),
        message: "not a file path".into(),
    })?;
    let temp = path.with_file_name(format!(
        ".{}.{}-{}.tmp",
        name.to_string_lossy(),
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let result = (|| {
        let mut out = BufWriter::new(File::create(&temp)?);
        write(&mut out)?;
        out.into_inner().map_err(io::IntoInnerError::into_error)?;
        fs::rename(&temp, path)
    })();
    result.map_err(|e| {
        // Best effort: the temporary may not exist if creating it failed.
        let _ = fs::remove_file(&temp);
        MeshError::io(path, e)
    })
}
