//! One run per output folder at a time: an exclusive OS advisory lock (`flock(2)`, through
//! `rustix`) on the file `.NAME.lock` beside the folder. The OS releases it when the run ends
//! or dies, so a held lock means a live run, and a free one means that whatever temporaries
//! the folder has are a dead run's. (Where there is no `flock`, outside Unix, nothing is
//! locked.)

use crate::error::SceneError;
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};

/// A held lock on an output folder; dropping it removes the lock file and releases it.
#[derive(Debug)]
pub(super) struct OutputLock {
    file: File,
    path: PathBuf,
}

impl OutputLock {
    /// Takes the lock `path` of the output folder `dest`, or says which run holds it.
    pub fn acquire(path: &Path, dest: &Path) -> Result<OutputLock, SceneError> {
        loop {
            let file = OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(path)
                .map_err(|e| unwritable(dest, path, e))?;
            match try_lock(&file) {
                Ok(true) => {}
                Ok(false) => {
                    let holder = std::fs::read_to_string(path).unwrap_or_default();
                    let holder = holder.trim();
                    return Err(SceneError::Output(format!(
                        "another isochor run{} is writing into {} (it holds {}): wait for it \
                         to end or choose another --out",
                        if holder.is_empty() {
                            String::new()
                        } else {
                            format!(" (process {holder})")
                        },
                        dest.display(),
                        path.display()
                    )));
                }
                Err(e) => return Err(SceneError::io(path, e)),
            }
            // A run that released the lock removes its file first: if `path` is no longer
            // the file locked, lock the one there now.
            if is_the_file_at(&file, path) {
                let mut lock = OutputLock {
                    file,
                    path: path.to_path_buf(),
                };
                lock.record_holder();
                return Ok(lock);
            }
        }
    }

    /// Writes this process's id into the lock file, for the message a second run prints.
    fn record_holder(&mut self) {
        // Best effort: the id only makes the refusal clearer.
        let _ = self.file.set_len(0);
        let _ = writeln!(self.file, "{}", std::process::id());
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        // Removed while still held, so a run that opened it meanwhile sees it gone.
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Takes an exclusive lock on `file` without waiting: `false` if another open file holds it.
#[cfg(unix)]
fn try_lock(file: &File) -> std::io::Result<bool> {
    use rustix::fs::{flock, FlockOperation};
    match flock(file, FlockOperation::NonBlockingLockExclusive) {
        Ok(()) => Ok(true),
        Err(e) if e == rustix::io::Errno::WOULDBLOCK => Ok(false),
        Err(e) => Err(e.into()),
    }
}

/// No lock where there is no `flock`.
#[cfg(not(unix))]
fn try_lock(_file: &File) -> std::io::Result<bool> {
    Ok(true)
}

/// Whether `path` still names the open `file`.
#[cfg(unix)]
fn is_the_file_at(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

/// Whether `path` still names the open `file` (assumed where file identities are not
/// compared).
#[cfg(not(unix))]
fn is_the_file_at(_file: &File, path: &Path) -> bool {
    path.is_file()
}

/// The error of an output folder beside which nothing can be written.
pub(super) fn unwritable(dest: &Path, path: &Path, e: std::io::Error) -> SceneError {
    let parent = path.parent().unwrap_or(Path::new("."));
    SceneError::Output(format!(
        "cannot write the output folder {}: {} is not writable ({e})",
        dest.display(),
        parent.display()
    ))
}
