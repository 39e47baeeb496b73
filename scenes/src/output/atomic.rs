//! An output folder that appears whole or not at all.

use crate::error::SceneError;
use std::path::{Path, PathBuf};

/// The file name of a run's checkpoint in its output folder: a folder holding one is an
/// unfinished run, kept to be resumed.
pub const CHECKPOINT_FILE: &str = "checkpoint.toml";

/// Files that mark a folder as an isochor output folder (so it may be replaced).
const MARKERS: [&str; 4] = ["summary.json", "compare.csv", "study.csv", "penalties.csv"];

/// A temporary folder `.NAME.tmp` next to the destination; [`OutputDir::commit`] renames it
/// to the destination, and dropping it uncommitted removes it, unless it holds a checkpoint
/// (then `isochor resume` continues the run in it). The name is fixed per destination, so
/// the folder a killed run left behind is removed by the next run into the same destination
/// (two runs into one destination at once are not supported).
#[derive(Debug)]
pub struct OutputDir {
    temp: PathBuf,
    dest: PathBuf,
    committed: bool,
}

impl OutputDir {
    /// Prepares an output folder for `dest`. Fails at once (before any work) if `dest` is a
    /// file, or an existing non-empty folder that is not an earlier isochor output.
    pub fn create(dest: &Path) -> Result<OutputDir, SceneError> {
        check_replaceable(dest)?;
        let temp = temporary(dest)?;
        if let Some(parent) = temp.parent() {
            std::fs::create_dir_all(parent).map_err(|e| SceneError::io(parent, e))?;
        }
        // Left behind by an earlier run that was killed (or by a failed commit).
        for stale in [&temp, &temp.with_extension("old")] {
            if stale.symlink_metadata().is_ok() {
                remove(stale)?;
            }
        }
        std::fs::create_dir(&temp).map_err(|e| SceneError::io(&temp, e))?;
        Ok(OutputDir {
            temp,
            dest: dest.to_path_buf(),
            committed: false,
        })
    }

    /// The unfinished output folder of an interrupted run into `dest`, as it was left.
    pub fn reopen(dest: &Path) -> Result<OutputDir, SceneError> {
        let temp = temporary(dest)?;
        if !temp.join(CHECKPOINT_FILE).is_file() {
            let finished = dest.join(CHECKPOINT_FILE).is_file();
            return Err(SceneError::Output(if finished {
                format!("the run in {} has already finished", dest.display())
            } else {
                format!(
                    "no interrupted run to resume in {} (a run keeps one only with --checkpoint-every)",
                    dest.display()
                )
            }));
        }
        Ok(OutputDir {
            temp,
            dest: dest.to_path_buf(),
            committed: false,
        })
    }

    /// The temporary folder to write into.
    pub fn path(&self) -> &Path {
        &self.temp
    }

    /// The final destination.
    pub fn destination(&self) -> &Path {
        &self.dest
    }

    /// Moves the finished outputs to the destination (replacing an earlier output there).
    pub fn commit(mut self) -> Result<PathBuf, SceneError> {
        check_replaceable(&self.dest)?;
        let old = self.temp.with_extension("old");
        if self.dest.exists() {
            std::fs::rename(&self.dest, &old).map_err(|e| SceneError::io(&self.dest, e))?;
        }
        std::fs::rename(&self.temp, &self.dest).map_err(|e| SceneError::io(&self.dest, e))?;
        self.committed = true;
        if old.exists() {
            std::fs::remove_dir_all(&old).map_err(|e| SceneError::io(&old, e))?;
        }
        Ok(self.dest.clone())
    }
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        if !self.committed && !self.temp.join(CHECKPOINT_FILE).is_file() {
            let _ = std::fs::remove_dir_all(&self.temp);
        }
    }
}

/// The hidden folder `.NAME.tmp` next to `dest` that a run writes into.
fn temporary(dest: &Path) -> Result<PathBuf, SceneError> {
    let name = dest
        .file_name()
        .ok_or_else(|| SceneError::Output(format!("{} is not a folder name", dest.display())))?
        .to_string_lossy()
        .into_owned();
    let parent = match dest.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok(parent.join(format!(".{name}.tmp")))
}

/// Removes a stale temporary folder (or a file or link in its place).
fn remove(path: &Path) -> Result<(), SceneError> {
    let result = if path.is_dir() && !path.is_symlink() {
        std::fs::remove_dir_all(path)
    } else {
        std::fs::remove_file(path)
    };
    result.map_err(|e| SceneError::io(path, e))
}

fn check_replaceable(dest: &Path) -> Result<(), SceneError> {
    if !dest.exists() {
        return Ok(());
    }
    if !dest.is_dir() {
        return Err(SceneError::Output(format!(
            "{} exists and is not a folder",
            dest.display()
        )));
    }
    let mut entries = std::fs::read_dir(dest).map_err(|e| SceneError::io(dest, e))?;
    let empty = entries.next().is_none();
    if empty || MARKERS.iter().any(|m| dest.join(m).is_file()) {
        Ok(())
    } else {
        Err(SceneError::Output(format!(
            "{} exists and is not an isochor output folder (no {}); choose another --out",
            dest.display(),
            MARKERS.join(" or ")
        )))
    }
}

/// Writes a whole file.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), SceneError> {
    std::fs::write(path, bytes).map_err(|e| SceneError::io(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("isochor-atomic-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn uncommitted_output_leaves_nothing() {
        let root = scratch("drop");
        let dest = root.join("out");
        {
            let out = OutputDir::create(&dest).unwrap();
            std::fs::write(out.path().join("a.txt"), "x").unwrap();
        }
        assert!(!dest.exists());
        assert_eq!(std::fs::read_dir(&root).unwrap().count(), 0);
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn commit_replaces_an_earlier_output_but_not_a_foreign_folder() {
        let root = scratch("commit");
        let dest = root.join("out");
        for round in 0..2 {
            let out = OutputDir::create(&dest).unwrap();
            std::fs::write(out.path().join("summary.json"), format!("{round}")).unwrap();
            out.commit().unwrap();
            assert_eq!(
                std::fs::read_to_string(dest.join("summary.json")).unwrap(),
                format!("{round}")
            );
        }
        assert_eq!(std::fs::read_dir(&root).unwrap().count(), 1);
        let foreign = root.join("mine");
        std::fs::create_dir(&foreign).unwrap();
        std::fs::write(foreign.join("thesis.tex"), "x").unwrap();
        assert!(OutputDir::create(&foreign).is_err());
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_killed_runs_temporary_folder_is_removed_by_the_next_run() {
        let root = scratch("stale");
        let dest = root.join("out");
        let stale = root.join(".out.tmp");
        std::fs::create_dir(&stale).unwrap();
        std::fs::write(stale.join("frame_0.vtu"), "partial").unwrap();
        std::fs::write(root.join(".out.old"), "a file in the way").unwrap();
        let out = OutputDir::create(&dest).unwrap();
        assert_eq!(out.path(), stale);
        assert_eq!(std::fs::read_dir(out.path()).unwrap().count(), 0);
        std::fs::write(out.path().join("summary.json"), "{}").unwrap();
        out.commit().unwrap();
        let names: Vec<_> = std::fs::read_dir(&root)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, ["out"]);
        std::fs::remove_dir_all(&root).unwrap();
    }
}
