//! The output folder checked before any work: a command whose `--out` cannot be written as a
//! whole folder (as [`crate::artifacts`] writes it) is refused at once with exit 2, naming the folder
//! and the reason, instead of after minutes of computing.

use crate::error::AppError;
use std::path::{Path, PathBuf};

/// The file that marks a folder as friction-lab's output (replaceable by the next run).
pub const MARKER: &str = ".friction-lab-output";

/// Prefix of the temporary folders (and of the folder set aside while swapping), reserved:
/// an output folder may not begin with it.
pub const TEMPORARY_PREFIX: &str = ".friction-lab-";

/// The longest name of one folder, in bytes: the limit of the common file systems (NAME_MAX
/// of ext4, XFS, btrfs, APFS and NTFS's 255 UTF-16 units at worst).
pub const NAME_MAX: usize = 255;

/// Checks that `root` can be written as friction-lab's output folder: a name of its own (not
/// `.`, `..` or `/`), at most [`NAME_MAX`] bytes, without the reserved temporary prefix; not a
/// symbolic link, a file or a device; absent, empty, or a folder friction-lab wrote that holds
/// no file it did not write (any, with `replace`: they are deleted with it; [`foreign_files`]);
/// not a mount point (the folder is replaced whole by a rename); and its nearest existing
/// ancestor a folder in which a temporary folder can be made (and is removed at once). Nothing
/// else is created.
pub fn check(root: &Path, replace: bool) -> Result<(), AppError> {
    let refuse = |why: String| AppError::OutputFolder {
        path: root.to_path_buf(),
        why,
    };
    let Some(name) = root.file_name() else {
        return Err(refuse(
            "it names no folder of its own: friction-lab replaces its output folder whole, so \
             name a folder to create or replace (e.g. `results`)"
                .into(),
        ));
    };
    let name = name.to_string_lossy();
    if name.len() > NAME_MAX {
        return Err(refuse(format!(
            "its name is {} bytes long: allowed at most {NAME_MAX}",
            name.len()
        )));
    }
    if name.starts_with(TEMPORARY_PREFIX) {
        return Err(refuse(format!(
            "names beginning `{TEMPORARY_PREFIX}` are friction-lab's temporary folders, which \
             the next run beside them removes: choose another name"
        )));
    }
    match std::fs::symlink_metadata(root) {
        // Absent, or under a file: the folders above it say why (`writable_beside`).
        Err(e)
            if matches!(
                e.kind(),
                std::io::ErrorKind::NotFound | std::io::ErrorKind::NotADirectory
            ) => {}
        Err(e) => return Err(refuse(format!("it cannot be examined: {e}"))),
        Ok(meta) if meta.file_type().is_symlink() => {
            let target = std::fs::read_link(root).map_or_else(
                |_| String::from("an unreadable target"),
                |t| format!("`{}`", t.display()),
            );
            return Err(refuse(format!(
                "it is a symbolic link (to {target}): friction-lab replaces its output folder \
                 whole, which would replace the link; name the folder itself"
            )));
        }
        Ok(meta) if !meta.is_dir() => {
            return Err(refuse("it exists and is not a folder".into()));
        }
        Ok(meta) => {
            existing_folder(root, replace)?;
            if mount_point(root, &meta) {
                return Err(refuse(
                    "it is a mount point: friction-lab replaces its output folder whole, which \
                     a mount point cannot be; name a folder inside it"
                        .into(),
                ));
            }
        }
    }
    writable_beside(root)
}

/// The checks of a folder `root` that exists: one friction-lab wrote (it holds [`MARKER`])
/// and that holds no file it did not write unless `replace`, or an empty one.
fn existing_folder(root: &Path, replace: bool) -> Result<(), AppError> {
    let refuse = |why: String| AppError::OutputFolder {
        path: root.to_path_buf(),
        why,
    };
    if root.join(MARKER).is_file() {
        let foreign = foreign_files(root);
        if foreign.is_empty() || replace {
            return Ok(());
        }
        let shown: Vec<String> = (foreign.iter().take(SHOWN_FOREIGN))
            .map(|p| format!("`{}`", p.display()))
            .collect();
        let more = match foreign.len().saturating_sub(SHOWN_FOREIGN) {
            0 => String::new(),
            n => format!(" and {n} more"),
        };
        return Err(refuse(format!(
            "friction-lab wrote it, but it now holds {} that friction-lab did not write ({}{more}), \
             which replacing the folder would delete: move them out, choose another folder, or \
             pass {} to replace the folder with them",
            if foreign.len() == 1 { "a file" } else { "files" },
            shown.join(", "),
            crate::error::field("replace")
        )));
    }
    let empty = std::fs::read_dir(root)
        .map_err(|e| refuse(format!("it cannot be read: {e}")))?
        .next()
        .is_none();
    if empty {
        Ok(())
    } else {
        Err(refuse(format!(
            "it is a folder that friction-lab did not write and it is not empty (no {MARKER} \
             in it): choose a new or empty folder"
        )))
    }
}

/// How many of the files friction-lab did not write a refusal names.
const SHOWN_FOREIGN: usize = 5;

/// The line of [`MARKER`] after which it lists the files of its folder, one path (relative to
/// the folder) per line.
pub const FILES_LINE: &str = "files:";

/// The files inside the folder `root` (friction-lab's output: it holds [`MARKER`]) that its
/// marker does not list, by their paths inside it, sorted; none where the marker lists no
/// files (one written before markers listed them: what it wrote is not known).
pub fn foreign_files(root: &Path) -> Vec<PathBuf> {
    let Ok(marker) = std::fs::read_to_string(root.join(MARKER)) else {
        return Vec::new();
    };
    let mut lines = marker.lines();
    if !lines.any(|l| l == FILES_LINE) {
        return Vec::new();
    }
    let listed: std::collections::BTreeSet<PathBuf> = lines.map(PathBuf::from).collect();
    let mut found = Vec::new();
    let mut pending = vec![PathBuf::new()];
    while let Some(dir) = pending.pop() {
        let Ok(entries) = std::fs::read_dir(root.join(&dir)) else {
            continue;
        };
        for entry in entries.flatten() {
            let relative = dir.join(entry.file_name());
            match entry.file_type() {
                Ok(kind) if kind.is_dir() => pending.push(relative),
                _ if relative == Path::new(MARKER) || listed.contains(&relative) => {}
                _ => found.push(relative),
            }
        }
    }
    found.sort();
    found
}

/// A claim on an output folder for the whole run of a command: an advisory lock on a file
/// `.friction-lab-HASH.lock` in the nearest folder above it that exists, HASH naming the rest
/// of its path ([`claim`]). Dropping it removes the file, while still holding the lock.
#[derive(Debug)]
pub struct Claim {
    lock: std::fs::File,
    path: PathBuf,
}

impl Drop for Claim {
    fn drop(&mut self) {
        // Removed while locked: a run that opened it meanwhile sees, once it holds the lock,
        // that the path no longer names its file, and starts over ([`claim`]).
        let _ = std::fs::remove_file(&self.path);
        let _ = self.lock.unlock();
    }
}

/// Claims `root` for this run ([`Claim`]): a second run writing the same folder is refused
/// while the first runs, naming it, rather than one silently replacing the other's result at
/// the end. Nothing is created but the lock file, which the claim removes when dropped.
pub fn claim(root: &Path) -> Result<Claim, AppError> {
    let refuse = |why: String| AppError::OutputFolder {
        path: root.to_path_buf(),
        why,
    };
    // The nearest existing folder above `root`, and the path from it to `root`.
    let mut base = parent_of(root);
    let mut rest = PathBuf::from(root.file_name().unwrap_or_default());
    while !base.is_dir() {
        match (base.parent(), base.file_name()) {
            (Some(p), Some(name)) if !p.as_os_str().is_empty() => {
                rest = Path::new(name).join(rest);
                base = p.to_path_buf();
            }
            _ => {
                rest = base.join(rest);
                base = PathBuf::from(".");
                break;
            }
        }
    }
    // FNV-1a of the rest of the path: one name per output folder, within NAME_MAX.
    let hash = (rest.to_string_lossy().bytes()).fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
    });
    let path = base.join(format!("{TEMPORARY_PREFIX}{hash:016x}.lock"));
    let io = |e: std::io::Error| {
        refuse(format!(
            "its lock `{}` cannot be taken: {e}",
            path.display()
        ))
    };
    loop {
        let lock = std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
            .map_err(io)?;
        match lock.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                return Err(refuse(
                    "another friction-lab run is writing it now: wait for it to end, or \
                     choose another folder"
                        .into(),
                ))
            }
            Err(std::fs::TryLockError::Error(e)) => return Err(io(e)),
        }
        if same_file(&lock, &path) {
            return Ok(Claim { lock, path });
        }
        // The run that held it removed it before this one locked it: start over.
    }
}

/// Whether `path` still names the open `file` (its lock is then the path's).
#[cfg(unix)]
fn same_file(file: &std::fs::File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

/// Whether `path` still names the open `file`: taken as so where the platform cannot tell.
#[cfg(not(unix))]
fn same_file(_file: &std::fs::File, path: &Path) -> bool {
    path.exists()
}

/// Whether the folder `root` (of metadata `meta`) is a mount point: on another device than
/// its parent, or (a bind mount of the same device) listed as one in the system's mount
/// table ([`listed_mount_point`]).
#[cfg(unix)]
fn mount_point(root: &Path, meta: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    let parent = parent_of(root);
    std::fs::metadata(parent).is_ok_and(|p| p.dev() != meta.dev()) || listed_mount_point(root)
}

/// Whether `root`, made absolute with its links resolved, is the mount point of a line of
/// `/proc/self/mountinfo` (Linux: the fifth field, with spaces and the like written `\040`;
/// elsewhere the file is absent and nothing is listed).
#[cfg(unix)]
fn listed_mount_point(root: &Path) -> bool {
    let (Ok(table), Ok(root)) = (
        std::fs::read_to_string("/proc/self/mountinfo"),
        std::fs::canonicalize(root),
    ) else {
        return false;
    };
    table
        .lines()
        .filter_map(|line| line.split(' ').nth(4))
        .any(|field| Path::new(&unescape_octal(field)) == root)
}

/// A field of the mount table with its octal escapes (`\040` for a space) undone.
#[cfg(unix)]
fn unescape_octal(field: &str) -> String {
    let bytes = field.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let octal = bytes
            .get(i + 1..i + 4)
            .filter(|d| bytes[i] == b'\\' && d.iter().all(|c| (b'0'..=b'7').contains(c)));
        match octal {
            Some(d) => {
                out.push(d.iter().fold(0u8, |n, c| n.wrapping_mul(8) + (c - b'0')));
                i += 4;
            }
            None => {
                out.push(bytes[i]);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Whether the folder `root` is a mount point: not known on this platform; the rename into
/// place says so, later.
#[cfg(not(unix))]
fn mount_point(_root: &Path, _meta: &std::fs::Metadata) -> bool {
    false
}

/// The folder that holds `root` (`.` for a bare name).
fn parent_of(root: &Path) -> PathBuf {
    match root.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Proves that the folders above `root` can take it: the nearest existing ancestor is a folder
/// in which a temporary folder can be made (it is removed at once).
fn writable_beside(root: &Path) -> Result<(), AppError> {
    let refuse = |why: String| AppError::OutputFolder {
        path: root.to_path_buf(),
        why,
    };
    let mut ancestor = parent_of(root);
    while std::fs::symlink_metadata(&ancestor).is_err() {
        match ancestor.parent() {
            Some(p) if !p.as_os_str().is_empty() => ancestor = p.to_path_buf(),
            _ => {
                ancestor = PathBuf::from(".");
                break;
            }
        }
    }
    if !ancestor.is_dir() {
        return Err(refuse(format!(
            "`{}` above it is not a folder",
            ancestor.display()
        )));
    }
    tempfile::Builder::new()
        .prefix(TEMPORARY_PREFIX)
        .tempdir_in(&ancestor)
        .map(drop)
        .map_err(|e| {
            // The system's reason, without the name of the temporary folder it tried.
            let reason = e.raw_os_error().map_or_else(
                || e.kind().to_string(),
                |code| std::io::Error::from_raw_os_error(code).to_string(),
            );
            refuse(format!(
                "nothing can be written in `{}`, the folder that would hold it: {reason}",
                ancestor.display()
            ))
        })
}

#[cfg(all(test, unix))]
mod tests {
    use super::{claim, unescape_octal};

    #[test]
    fn a_folder_claimed_by_a_run_is_refused_to_another_until_the_first_ends() {
        let dir = tempfile::tempdir().unwrap();
        // The folder and the one above it do not exist yet: the lock is in `dir`.
        let out = dir.path().join("runs").join("results");
        let first = claim(&out).unwrap();
        let second = claim(&out).unwrap_err().to_string();
        assert!(
            second.contains("another friction-lab run is writing it now"),
            "{second}"
        );
        // Another folder is free; nothing but the two lock files was made.
        let other = claim(&dir.path().join("other")).unwrap();
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
        drop((first, other));
        // Released and removed: the folder can be claimed again, and nothing is left.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        drop(claim(&out).unwrap());
    }

    #[test]
    fn the_mount_tables_escapes_are_undone() {
        assert_eq!(unescape_octal("/mnt/my\\040disk"), "/mnt/my disk");
        assert_eq!(unescape_octal("/a\\011b\\134c"), "/a\tb\\c");
        // Not an escape: left as it is.
        assert_eq!(unescape_octal("/a\\9x\\04"), "/a\\9x\\04");
    }
}
