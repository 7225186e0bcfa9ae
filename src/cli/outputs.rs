//! The policy for every file a command writes. Before anything is solved or replayed, each
//! output path is resolved (symbolic links and `..` followed), and the command is refused
//! (exit 2) where two outputs name one file, where an output names one of the command's inputs
//! (the case file, the MCAP log being replayed), or where an output's folder does not exist or
//! cannot be written. While the command runs it holds an exclusive lock on each output: a
//! second run writing the same file is refused at once, naming the file, instead of
//! interleaving its writes with the first's. A study holds a lock on its whole folder
//! ([`claim_folder`]).

use std::fs::{File, OpenOptions, TryLockError};
use std::path::{Path, PathBuf};

/// A file a command reads or writes, with the option or role that names it.
pub struct Named<'a> {
    pub role: &'a str,
    pub path: &'a Path,
}

/// Locks held on a command's outputs until it ends. A file that the claim created and that is
/// still empty when the locks go (the command stopped before writing it) is removed again.
pub struct Locks(Vec<Held>);

struct Held {
    /// Kept open: the lock lasts as long as the file handle.
    file: File,
    path: PathBuf,
    created: bool,
}

impl Locks {
    /// The outputs that held a file before the claim (an earlier run's, which this one replaces).
    pub fn replaced(&self) -> Vec<&Path> {
        self.0
            .iter()
            .filter(|held| !held.created && held.file.metadata().is_ok_and(|m| m.len() > 0))
            .map(|held| held.path.as_path())
            .collect()
    }
}

impl Drop for Locks {
    fn drop(&mut self) {
        use std::os::unix::fs::MetadataExt;
        for held in &self.0 {
            // Only the file the claim created: a resumed run renames its continued file over it.
            let same = std::fs::metadata(&held.path)
                .ok()
                .zip(held.file.metadata().ok())
                .is_some_and(|(now, locked)| now.ino() == locked.ino() && now.dev() == locked.dev());
            if held.created && same && held.file.metadata().is_ok_and(|m| m.len() == 0) {
                let _ = std::fs::remove_file(&held.path);
            }
        }
    }
}

/// Checks the outputs against each other and against the inputs, checks their folders, and
/// locks them. The error names both paths or the folder, and what to do.
pub fn claim(inputs: &[Named<'_>], outputs: &[Named<'_>]) -> Result<Locks, String> {
    let resolved: Vec<PathBuf> = outputs.iter().map(|o| resolve(o.path)).collect();
    for (i, output) in outputs.iter().enumerate() {
        if let Some(j) = (0..i).find(|&j| resolved[j] == resolved[i]) {
            return Err(format!(
                "{} {} and {} {} name the same file: give each output its own path",
                outputs[j].role,
                outputs[j].path.display(),
                output.role,
                output.path.display()
            ));
        }
        if let Some(input) = inputs.iter().find(|input| resolve(input.path) == resolved[i]) {
            return Err(format!(
                "{} {} would overwrite the {} it reads ({}): write it elsewhere",
                output.role,
                output.path.display(),
                input.role,
                input.path.display()
            ));
        }
        check_folder(output)?;
    }
    outputs.iter().map(lock).collect::<Result<Vec<_>, _>>().map(Locks)
}

/// `path` made absolute, through its folder's canonical form where that exists (the file
/// itself may not exist yet).
fn resolve(path: &Path) -> PathBuf {
    if let Ok(canonical) = path.canonicalize() {
        return canonical;
    }
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    match (absolute.parent().and_then(|p| p.canonicalize().ok()), absolute.file_name()) {
        (Some(folder), Some(name)) => folder.join(name),
        _ => absolute,
    }
}

/// The output's folder exists and a file can be created in it.
fn check_folder(output: &Named<'_>) -> Result<(), String> {
    let folder = match output.path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !folder.is_dir() {
        return Err(format!(
            "{} {}: the folder {} does not exist",
            output.role,
            output.path.display(),
            folder.display()
        ));
    }
    check_writable(folder)
        .map_err(|e| format!("{} {}: cannot write in {}: {e}", output.role, output.path.display(), folder.display()))
}

/// A file can be created (and removed) in `dir`. The probe's name is this call's own, so that
/// threads checking one folder at once (a study's members) do not remove each other's.
pub fn check_writable(dir: &Path) -> std::io::Result<()> {
    static PROBES: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = PROBES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let probe = dir.join(format!(".slipfront-write-test-{}-{n}", std::process::id()));
    std::fs::write(&probe, b"")?;
    std::fs::remove_file(&probe)
}

/// An exclusive lock on the output file (created empty if missing, never truncated here).
fn lock(output: &Named<'_>) -> Result<Held, String> {
    let describe = |e: std::io::Error| format!("{} {}: {e}", output.role, output.path.display());
    let created = !output.path.exists();
    let file = OpenOptions::new().create(true).truncate(false).write(true).open(output.path).map_err(describe)?;
    match file.try_lock() {
        Ok(()) => Ok(Held { file, path: output.path.to_path_buf(), created }),
        Err(TryLockError::WouldBlock) => Err(format!(
            "{} {} is being written by another slipfront command: wait for it, or write elsewhere",
            output.role,
            output.path.display()
        )),
        Err(TryLockError::Error(e)) => Err(describe(e)),
    }
}

/// A lock on a folder, held until dropped.
pub struct FolderLock(#[allow(dead_code)] File);

/// Locks the folder `dir` for a command that owns it (a study): exclusively, or with `shared`
/// alongside the other holders of a shared lock (the shards of one study, each of which claims
/// its own members' files). A second owner is refused at once, as a second writer of a file is.
pub fn claim_folder(dir: &Path, shared: bool) -> Result<FolderLock, String> {
    let folder = File::open(dir).map_err(|e| format!("cannot open {}: {e}", dir.display()))?;
    let locked = if shared { folder.try_lock_shared() } else { folder.try_lock() };
    match locked {
        Ok(()) => Ok(FolderLock(folder)),
        Err(TryLockError::WouldBlock) => Err(format!(
            "{} is being written by another slipfront study: wait for it to end, or give another --out-dir \
             (the shards of one study, --shard I/N, may share a folder)",
            dir.display()
        )),
        Err(TryLockError::Error(e)) => Err(format!("cannot lock {}: {e}", dir.display())),
    }
}
