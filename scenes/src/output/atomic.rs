//! An output folder that appears whole or not at all, and never replaces what is not
//! isochor's.
//!
//! A run into `DIR` holds the lock `.DIR.lock` ([`super::lock`]) and writes into `.DIR.tmp`
//! beside `DIR`. Its commit fsyncs every file and folder of `.DIR.tmp`, renames it to
//! `.DIR.new`, the earlier output `DIR` (if any) to `.DIR.old`, then `.DIR.new` to `DIR`, and
//! only then removes `.DIR.old`, syncing the parent folder after each rename. A run killed
//! anywhere in between leaves a state the next run (or `isochor resume`) into `DIR` completes
//! before doing anything else ([`recover`]): nothing is lost, whatever the moment.

use super::lock::{unwritable, OutputLock};
use super::marker::{is_marked, OutputIdentity, MARKER_FILE};
use crate::error::SceneError;
use std::fs::File;
use std::path::{Path, PathBuf};

/// The file name of a run's checkpoint in its output folder: a folder holding one is an
/// unfinished run, kept to be resumed.
pub const CHECKPOINT_FILE: &str = "checkpoint.toml";

/// The folders and files a run into one destination uses beside it.
#[derive(Debug, Clone)]
struct Paths {
    /// The destination, its symbolic link (if it was one) followed.
    dest: PathBuf,
    /// `.NAME.tmp`: the folder being written.
    temp: PathBuf,
    /// `.NAME.new`: the finished folder, synced, about to become `dest`.
    ready: PathBuf,
    /// `.NAME.old`: the earlier output while it is being replaced.
    old: PathBuf,
    /// `.NAME.lock`: the lock file.
    lock: PathBuf,
}

/// The output folder of one run: `.NAME.tmp` next to the destination, written after
/// [`OutputDir::start`], and moved to the destination by [`OutputDir::commit`]. Dropped
/// uncommitted, it is removed unless it holds a checkpoint (then `isochor resume` continues
/// the run in it). It holds the destination's lock until it is dropped.
#[derive(Debug)]
pub struct OutputDir {
    paths: Paths,
    identity: OutputIdentity,
    started: bool,
    committed: bool,
    _lock: OutputLock,
}

impl OutputDir {
    /// Prepares and starts an output folder for `dest` ([`OutputDir::prepare`], then
    /// [`OutputDir::start`]).
    pub fn create(dest: &Path, identity: OutputIdentity) -> Result<OutputDir, SceneError> {
        let mut dir = OutputDir::prepare(dest, identity)?;
        dir.start()?;
        Ok(dir)
    }

    /// Prepares an output folder for `dest` without writing into it: fails at once (before
    /// any work) if `dest` is a file, a dangling symbolic link, an existing non-empty folder
    /// that is not an isochor output (it has no `.isochor-output.json`), unwritable, or being
    /// written by another run; completes an interrupted commit into `dest`. A symbolic link
    /// `dest` is followed: the folder it points to is replaced, the link kept.
    pub fn prepare(dest: &Path, identity: OutputIdentity) -> Result<OutputDir, SceneError> {
        let paths = Paths::of(&follow_link(dest)?)?;
        check_replaceable(&paths.dest)?;
        let parent = parent(&paths.dest);
        std::fs::create_dir_all(&parent).map_err(|e| unwritable(dest, &paths.lock, e))?;
        let lock = OutputLock::acquire(&paths.lock, dest)?;
        recover(&paths)?;
        Ok(OutputDir {
            paths,
            identity,
            started: false,
            committed: false,
            _lock: lock,
        })
    }

    /// Starts writing: removes the temporary folder a dead run left (the lock shows it is
    /// dead) and creates an empty one holding the marker. Until this is called, an existing
    /// output and a resumable checkpoint are untouched.
    pub fn start(&mut self) -> Result<(), SceneError> {
        if self.started {
            return Ok(());
        }
        let temp = &self.paths.temp;
        if temp.symlink_metadata().is_ok() {
            remove(temp)?;
        }
        std::fs::create_dir(temp).map_err(|e| unwritable(&self.paths.dest, temp, e))?;
        self.started = true;
        self.identity.write(temp)
    }

    /// The unfinished output folder of an interrupted run into `dest`, as it was left (less
    /// the temporary files of its writes that the kill interrupted).
    pub fn reopen(dest: &Path) -> Result<OutputDir, SceneError> {
        let paths = Paths::of(&follow_link(dest)?)?;
        if !paths.temp.join(CHECKPOINT_FILE).is_file() {
            return Err(no_interrupted_run(&paths.dest));
        }
        let lock = OutputLock::acquire(&paths.lock, dest)?;
        recover(&paths)?;
        if !paths.temp.join(CHECKPOINT_FILE).is_file() {
            return Err(no_interrupted_run(&paths.dest));
        }
        remove_stale_temporaries(&paths.temp)?;
        Ok(OutputDir {
            paths,
            identity: OutputIdentity::new("run", ""),
            started: true,
            committed: false,
            _lock: lock,
        })
    }

    /// The temporary folder to write into.
    pub fn path(&self) -> &Path {
        &self.paths.temp
    }

    /// The final destination.
    pub fn destination(&self) -> &Path {
        &self.paths.dest
    }

    /// Moves the finished outputs to the destination, replacing an earlier output there only
    /// once the new one is synced and in place.
    pub fn commit(mut self) -> Result<PathBuf, SceneError> {
        self.start()?;
        let Paths {
            dest,
            temp,
            ready,
            old,
            ..
        } = self.paths.clone();
        check_replaceable(&dest)?;
        remove_stale_temporaries(&temp)?;
        sync_tree(&temp)?;
        rename(&temp, &ready)?;
        self.committed = true;
        if dest.exists() {
            rename(&dest, &old)?;
        }
        fault_point("commit-between-renames");
        rename(&ready, &dest)?;
        if old.symlink_metadata().is_ok() {
            remove(&old)?;
        }
        Ok(dest)
    }
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        let temp = &self.paths.temp;
        if self.started && !self.committed && !temp.join(CHECKPOINT_FILE).is_file() {
            let _ = std::fs::remove_dir_all(temp);
        }
    }
}

impl Paths {
    /// The paths of a run into `dest`.
    fn of(dest: &Path) -> Result<Paths, SceneError> {
        let name = dest
            .file_name()
            .ok_or_else(|| SceneError::Output(format!("{} is not a folder name", dest.display())))?
            .to_string_lossy()
            .into_owned();
        let beside = |suffix: &str| parent(dest).join(format!(".{name}.{suffix}"));
        Ok(Paths {
            dest: dest.to_path_buf(),
            temp: beside("tmp"),
            ready: beside("new"),
            old: beside("old"),
            lock: beside("lock"),
        })
    }
}

/// Completes what a run killed during its commit left (the caller holds the lock): a synced
/// `.NAME.new` becomes the destination, an earlier output left as `.NAME.old` is put back if
/// the destination is missing, and removed otherwise.
fn recover(paths: &Paths) -> Result<(), SceneError> {
    let Paths {
        dest, ready, old, ..
    } = paths;
    let exists = |p: &Path| p.symlink_metadata().is_ok();
    if exists(ready) {
        if exists(dest) {
            if exists(old) {
                remove(old)?;
            }
            rename(dest, old)?;
        }
        rename(ready, dest)?;
    } else if exists(old) && !exists(dest) {
        rename(old, dest)?;
    }
    if exists(old) {
        remove(old)?;
    }
    Ok(())
}

/// `dest`, or the folder it points to if it is a symbolic link; a dangling link is refused.
fn follow_link(dest: &Path) -> Result<PathBuf, SceneError> {
    let is_link = dest.symlink_metadata().is_ok_and(|m| m.is_symlink());
    if !is_link {
        return Ok(dest.to_path_buf());
    }
    std::fs::canonicalize(dest).map_err(|e| {
        let target = std::fs::read_link(dest).unwrap_or_default();
        SceneError::Output(format!(
            "{} is a symbolic link to {}, which cannot be followed ({e}); create the folder \
             it points to or choose another --out",
            dest.display(),
            target.display()
        ))
    })
}

/// The folder `dest` is in.
fn parent(dest: &Path) -> PathBuf {
    match dest.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn no_interrupted_run(dest: &Path) -> SceneError {
    let finished = dest.join(CHECKPOINT_FILE).is_file();
    SceneError::Output(if finished {
        format!("the run in {} has already finished", dest.display())
    } else {
        format!(
            "no interrupted run to resume in {} (a run keeps one only with --checkpoint-every)",
            dest.display()
        )
    })
}

/// Renames `from` to `to` and syncs their folder, so the rename survives a crash.
fn rename(from: &Path, to: &Path) -> Result<(), SceneError> {
    std::fs::rename(from, to).map_err(|e| SceneError::io(to, e))?;
    sync(&parent(to))
}

/// Removes a stale folder (or a file or link in its place).
fn remove(path: &Path) -> Result<(), SceneError> {
    let result = if path.is_dir() && !path.is_symlink() {
        std::fs::remove_dir_all(path)
    } else {
        std::fs::remove_file(path)
    };
    result.map_err(|e| SceneError::io(path, e))
}

/// Removes the temporary files of writes a dead run did not finish (`.NAME.PID-N.tmp` of
/// the frames, `checkpoint.toml.new`) from `dir`.
fn remove_stale_temporaries(dir: &Path) -> Result<(), SceneError> {
    let entries = std::fs::read_dir(dir).map_err(|e| SceneError::io(dir, e))?;
    for entry in entries {
        let entry = entry.map_err(|e| SceneError::io(dir, e))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let partial = name.starts_with('.') && name.ends_with(".tmp");
        if partial || name == format!("{CHECKPOINT_FILE}.new") {
            remove(&entry.path())?;
        }
    }
    Ok(())
}

/// Fsyncs every file and folder under `dir`, `dir` included.
fn sync_tree(dir: &Path) -> Result<(), SceneError> {
    let entries = std::fs::read_dir(dir).map_err(|e| SceneError::io(dir, e))?;
    for entry in entries {
        let entry = entry.map_err(|e| SceneError::io(dir, e))?;
        let kind = entry
            .file_type()
            .map_err(|e| SceneError::io(entry.path(), e))?;
        if kind.is_dir() {
            sync_tree(&entry.path())?;
        } else if kind.is_file() {
            sync(&entry.path())?;
        }
    }
    sync(dir)
}

/// Fsyncs one file or folder.
fn sync(path: &Path) -> Result<(), SceneError> {
    File::open(path)
        .and_then(|f| f.sync_all())
        .map_err(|e| SceneError::io(path, e))
}

/// A test hook of debug builds: with `ISOCHOR_FAULT=POINT` in the environment the process
/// aborts at `POINT`, as if it were killed there.
fn fault_point(point: &str) {
    if cfg!(debug_assertions) && std::env::var("ISOCHOR_FAULT").is_ok_and(|v| v == point) {
        eprintln!("isochor: ISOCHOR_FAULT={point}: aborting");
        std::process::abort();
    }
}

/// Refuses a destination that exists and is a file, or a non-empty folder without the
/// marker.
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
    if entries.next().is_none() || is_marked(dest) {
        Ok(())
    } else {
        Err(SceneError::Output(format!(
            "{} exists and is not an isochor output folder (it has no {MARKER_FILE}); it is \
             left as it is: choose another --out",
            dest.display()
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

    fn id() -> OutputIdentity {
        OutputIdentity::new("test", "")
    }

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
            let out = OutputDir::create(&dest, id()).unwrap();
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
            let out = OutputDir::create(&dest, id()).unwrap();
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
        assert!(OutputDir::create(&foreign, id()).is_err());
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_killed_runs_temporary_folder_is_removed_by_the_next_run() {
        let root = scratch("stale");
        let dest = root.join("out");
        let stale = root.join(".out.tmp");
        std::fs::create_dir(&stale).unwrap();
        std::fs::write(stale.join("frame_0.vtu"), "partial").unwrap();
        let out = OutputDir::create(&dest, id()).unwrap();
        assert_eq!(out.path(), stale);
        let names: Vec<_> = std::fs::read_dir(out.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, [MARKER_FILE]);
        std::fs::write(out.path().join(".frame_1.vtu.7-0.tmp"), "a dead write").unwrap();
        out.commit().unwrap();
        assert_eq!(names_in(&root), ["out"]);
        assert_eq!(names_in(&dest), [MARKER_FILE]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    fn names_in(dir: &Path) -> Vec<String> {
        let mut names: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    /// An output of round `round` into `dest`.
    fn output(dest: &Path, round: &str) {
        let out = OutputDir::create(dest, id()).unwrap();
        std::fs::write(out.path().join("summary.json"), round).unwrap();
        out.commit().unwrap();
    }

    fn summary(dir: &Path) -> String {
        std::fs::read_to_string(dir.join("summary.json")).unwrap()
    }

    /// Before: a folder with a `summary.json` counted as isochor's and was replaced whole,
    /// `thesis.tex` with it.
    #[test]
    fn a_folder_without_the_marker_is_refused_and_left_alone() {
        let root = scratch("foreign");
        let mine = root.join("mine");
        std::fs::create_dir(&mine).unwrap();
        std::fs::write(mine.join("summary.json"), "{}").unwrap();
        std::fs::write(mine.join("thesis.tex"), "x").unwrap();
        let err = OutputDir::prepare(&mine, id()).unwrap_err().to_string();
        assert!(err.contains("mine") && err.contains(MARKER_FILE), "{err}");
        assert_eq!(names_in(&mine), ["summary.json", "thesis.tex"]);
        assert_eq!(names_in(&root), ["mine"]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// Before: the link was replaced by a real folder; a dangling one failed after the run.
    #[cfg(unix)]
    #[test]
    fn a_linked_output_folder_is_followed_and_a_dangling_link_refused() {
        let root = scratch("link");
        let real = root.join("real");
        let link = root.join("link");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        let err = OutputDir::prepare(&link, id()).unwrap_err().to_string();
        assert!(
            err.contains("link") && err.contains("symbolic link"),
            "{err}"
        );
        std::fs::create_dir(&real).unwrap();
        output(&link, "1");
        output(&link, "2");
        assert!(link.symlink_metadata().unwrap().is_symlink());
        assert_eq!(summary(&real), "2");
        assert_eq!(names_in(&root), ["link", "real"]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// Each state a commit killed part way can leave is completed by the next run into the
    /// folder, which loses neither output. Before: the next run deleted `.NAME.old` and
    /// `.NAME.tmp`, and with them both outputs.
    #[test]
    fn an_interrupted_commit_is_completed_by_the_next_run() {
        let root = scratch("window");
        let dest = root.join("out");
        let ready = root.join(".out.new");
        let old = root.join(".out.old");
        // Killed after `.out.tmp` -> `.out.new`, before `out` -> `.out.old`.
        output(&dest, "old");
        std::fs::create_dir(&ready).unwrap();
        std::fs::write(ready.join("summary.json"), "new").unwrap();
        drop(OutputDir::prepare(&dest, id()).unwrap());
        assert_eq!(summary(&dest), "new");
        assert_eq!(names_in(&root), ["out"]);
        // Killed between the two renames: the new output in `.out.new`, the old in `.out.old`.
        std::fs::rename(&dest, &old).unwrap();
        std::fs::create_dir(&ready).unwrap();
        std::fs::write(ready.join("summary.json"), "newer").unwrap();
        drop(OutputDir::prepare(&dest, id()).unwrap());
        assert_eq!(summary(&dest), "newer");
        assert_eq!(names_in(&root), ["out"]);
        // A commit of an earlier version killed between its renames: only `.out.old`.
        std::fs::rename(&dest, &old).unwrap();
        drop(OutputDir::reopen(&dest).unwrap_err());
        drop(OutputDir::prepare(&dest, id()).unwrap());
        assert_eq!(summary(&dest), "newer");
        assert_eq!(names_in(&root), ["out"]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// A run that fails before it starts writing leaves the earlier output and an interrupted
    /// run's checkpoint as they were. Before: both were removed when the folder was created.
    #[test]
    fn a_run_that_never_starts_touches_nothing() {
        let root = scratch("unstarted");
        let dest = root.join("out");
        output(&dest, "old");
        let temp = root.join(".out.tmp");
        std::fs::create_dir(&temp).unwrap();
        std::fs::write(temp.join(CHECKPOINT_FILE), "resumable").unwrap();
        drop(OutputDir::prepare(&dest, id()).unwrap());
        assert_eq!(summary(&dest), "old");
        assert_eq!(names_in(&temp), [CHECKPOINT_FILE]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// Before: nothing stopped a second run, and the two mixed their frames.
    #[test]
    fn a_second_run_into_the_same_folder_is_refused() {
        let root = scratch("lock");
        let dest = root.join("out");
        let first = OutputDir::create(&dest, id()).unwrap();
        let err = OutputDir::prepare(&dest, id()).unwrap_err().to_string();
        assert!(err.contains("another isochor run"), "{err}");
        assert!(err.contains(&std::process::id().to_string()), "{err}");
        first.commit().unwrap();
        assert_eq!(names_in(&root), ["out"]);
        drop(OutputDir::prepare(&dest, id()).unwrap());
        std::fs::remove_dir_all(&root).unwrap();
    }
}
