//! ParaView `.pvd` collection: a time series of VTU frames, each of one or more parts.

use super::atomic::write_atomic;
use super::vtu::escape;
use crate::MeshError;
use std::io::Write;
use std::path::Path;

/// Writes the collection `path` listing `frames` as `(time, file)`; each file name is relative
/// to the directory of `path`. Rewriting it after every frame keeps a valid series on disk.
pub fn write_pvd(path: impl AsRef<Path>, frames: &[(f64, String)]) -> Result<(), MeshError> {
    let parts: Vec<(f64, usize, String)> = frames.iter().map(|(t, f)| (*t, 0, f.clone())).collect();
    write_pvd_parts(path, &parts)
}

/// Writes the collection `path` listing `frames` as `(time, part, file)`: the files of one
/// time with different `part` numbers are the blocks of one multiblock data set in
/// ParaView (e.g. a body and the surfaces of its obstacles).
pub fn write_pvd_parts(
    path: impl AsRef<Path>,
    frames: &[(f64, usize, String)],
) -> Result<(), MeshError> {
    let path = path.as_ref();
    if let Some((t, _, file)) = frames.iter().find(|(t, _, _)| !t.is_finite()) {
        return Err(MeshError::parameter(
            "time",
            t,
            format!("frame `{file}` needs a finite time"),
        ));
    }
    write_atomic(path, |w: &mut dyn Write| {
        writeln!(w, r#"<?xml version="1.0"?>"#)?;
        writeln!(
            w,
            r#"<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">"#
        )?;
        writeln!(w, "  <Collection>")?;
        for (t, part, file) in frames {
            writeln!(
                w,
                r#"    <DataSet timestep="{t:?}" group="" part="{part}" file="{}"/>"#,
                escape(file)
            )?;
        }
        writeln!(w, "  </Collection>")?;
        writeln!(w, "</VTKFile>")
    })
}
