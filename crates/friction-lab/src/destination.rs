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
/// symbolic link, a file or a device; absent, empty, or a folder friction-lab wrote; not a
/// mount point (the folder is replaced whole by a rename); and its nearest existing ancestor a
/// folder in which a temporary folder can be made (and is removed at once). Nothing else is
/// created.
pub fn check(root: &Path) -> Result<(), AppError> {
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
            existing_folder(root)?;
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

/// The checks of a folder `root` that exists: one friction-lab wrote (it holds [`MARKER`]), or
/// an empty one.
fn existing_folder(root: &Path) -> Result<(), AppError> {
    let refuse = |why: String| AppError::OutputFolder {
        path: root.to_path_buf(),
        why,
    };
    if root.join(MARKER).is_file() {
        return Ok(());
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
    use super::unescape_octal;

    #[test]
    fn the_mount_tables_escapes_are_undone() {
        assert_eq!(unescape_octal("/mnt/my\\040disk"), "/mnt/my disk");
        assert_eq!(unescape_octal("/a\\011b\\134c"), "/a\tb\\c");
        // Not an escape: left as it is.
        assert_eq!(unescape_octal("/a\\9x\\04"), "/a\\9x\\04");
    }
}
