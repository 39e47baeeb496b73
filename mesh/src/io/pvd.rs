//! ParaView `.pvd` collection: a time series of VTU frames.

use super::atomic::write_atomic;
use super::vtu::escape;
use crate::MeshError;
use std::io::Write;
use std::path::Path;

/// Writes the collection `path` listing `frames` as `(time, file)`; each file name is relative
/// to the directory of `path`. Rewriting it after every frame keeps a valid series on disk.
pub fn write_pvd(path: impl AsRef<Path>, frames: &[(f64, String)]) -> Result<(), MeshError> {
    let path = path.as_ref();
    if let Some((t, file)) = frames.iter().find(|(t, _)| !t.is_finite()) {
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
        for (t, file) in frames {
            writeln!(
                w,
                r#"    <DataSet timestep="{t:?}" group="" part="0" file="{}"/>"#,
                escape(file)
            )?;
        }
        writeln!(w, "  </Collection>")?;
        writeln!(w, "</VTKFile>")
    })
}
