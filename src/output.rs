//! The outputs of one command as one set ([`OutputSet`]): every output path is
//! checked and reserved before any work starts, written under a temporary
//! name next to its destination, and moved into place only when the whole
//! command succeeded. On any failure (an error, a panic, Ctrl-C, SIGTERM,
//! SIGHUP) every temporary file is removed, and so is every directory the set
//! created: a failed command writes nothing.
//!
//! - A file output (`--vcd x.vcd`) needs its parent directory to exist; it is
//!   reserved by creating its temporary file `x.vcd.<pid>.canstar-tmp`, which
//!   checks that the place is writable.
//! - A directory output (`--out`, `--vcd-dir`) is created if missing; files the
//!   command puts there are staged in `.canstar.<pid>.canstar-tmp/` inside it
//!   ([`OutputSet::dir`]) or reserved one by one ([`OutputSet::file_creating_dirs`]).
//! - [`OutputSet::commit`] renames the temporaries over their destinations with
//!   Ctrl-C and SIGTERM held off; the files it replaces are kept as hard links
//!   until every rename succeeded, so a failure half way restores the old set.
//!   (A SIGKILL inside that loop, microseconds long, can still leave a mix.)
//! - Temporaries left by a process that no longer runs (a SIGKILL, a power
//!   cut) are removed when a later command reserves an output in the same
//!   directory.

use anyhow::{anyhow, bail, Context, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, OnceLock};

/// Suffix of every temporary name (files, staging directories, backups).
pub const TMP_SUFFIX: &str = ".canstar-tmp";
const OLD_SUFFIX: &str = ".canstar-old";

/// Exit status after Ctrl-C, SIGTERM or SIGHUP.
pub const INTERRUPTED: i32 = 130;

/// What a set has on disk that a rollback removes.
#[derive(Default)]
struct Pending {
    /// Temporary files and staging directories.
    temps: Vec<PathBuf>,
    /// Directories the set created, in creation order (removed deepest first, if empty).
    created: Vec<PathBuf>,
}

impl Pending {
    fn rollback(&mut self) {
        for t in self.temps.drain(..) {
            if t.is_dir() {
                let _ = std::fs::remove_dir_all(&t);
            } else {
                let _ = std::fs::remove_file(&t);
            }
        }
        for d in self.created.drain(..).rev() {
            let _ = std::fs::remove_dir(&d);
        }
    }
}

#[derive(Default)]
struct Registry {
    sets: BTreeMap<u64, Pending>,
    /// A commit is renaming files: a signal waits for it.
    committing: bool,
    /// A signal arrived during a commit.
    interrupted: bool,
}

fn registry() -> MutexGuard<'static, Registry> {
    static R: OnceLock<Mutex<Registry>> = OnceLock::new();
    // A panic while the lock is held poisons it; the data is still usable.
    R.get_or_init(Default::default).lock().unwrap_or_else(|e| e.into_inner())
}

/// Install the Ctrl-C / SIGTERM / SIGHUP handler (once): it removes every
/// uncommitted output and exits with [`INTERRUPTED`], or, during a commit,
/// lets the commit finish first.
fn install_signal_handler() {
    static ONCE: OnceLock<()> = OnceLock::new();
    ONCE.get_or_init(|| {
        // Fails only if another handler is installed (not in this tool).
        let _ = ctrlc::set_handler(|| {
            let mut r = registry();
            if r.committing {
                r.interrupted = true;
                return;
            }
            for p in r.sets.values_mut() {
                p.rollback();
            }
            std::process::exit(INTERRUPTED);
        });
    });
}

/// Remove every uncommitted output of every set and exit with `code`.
pub fn abandon_and_exit(code: i32) -> ! {
    let mut r = registry();
    for p in r.sets.values_mut() {
        p.rollback();
    }
    std::process::exit(code)
}

/// Is any output still waiting for its commit?
pub fn uncommitted() -> bool {
    registry().sets.values().any(|p| !p.temps.is_empty())
}

/// Staged outputs of one command (see the module documentation).
pub struct OutputSet {
    id: u64,
    /// (destination as given, temporary file, file renamed over); for an
    /// existing device or FIFO (`/dev/null`, `/dev/stdout`) the temporary is
    /// the destination itself and nothing is renamed.
    files: Vec<(PathBuf, PathBuf, Option<PathBuf>)>,
    /// (destination directory, staging directory).
    dirs: Vec<(PathBuf, PathBuf)>,
    done: bool,
}

impl Default for OutputSet {
    fn default() -> Self {
        Self::new()
    }
}

fn pid() -> u32 {
    std::process::id()
}

/// `name.<pid>.canstar-tmp` next to `dest`.
fn tmp_name(dest: &Path) -> PathBuf {
    let name = dest.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    dest.with_file_name(format!("{name}.{}{TMP_SUFFIX}", pid()))
}

fn old_name(dest: &Path) -> PathBuf {
    let name = dest.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    dest.with_file_name(format!("{name}.{}{OLD_SUFFIX}", pid()))
}

/// Does a process with this id run? (Linux: `/proc/<pid>`; elsewhere assumed.)
fn alive(p: u32) -> bool {
    if cfg!(target_os = "linux") && Path::new("/proc/self").exists() {
        Path::new(&format!("/proc/{p}")).exists()
    } else {
        true
    }
}

/// Remove the temporaries and backups in `dir` left by processes that no
/// longer run (names `<anything>.<pid>.canstar-tmp` / `.canstar-old`; a name
/// without a pid, as older versions wrote, counts as stale).
pub fn clean_stale(dir: &Path) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for e in rd.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        let Some(stem) = name.strip_suffix(TMP_SUFFIX).or_else(|| name.strip_suffix(OLD_SUFFIX)) else { continue };
        let owner = stem.rsplit_once('.').and_then(|(_, p)| p.parse::<u32>().ok());
        if owner.is_some_and(|p| p == pid() || alive(p)) {
            continue;
        }
        let p = e.path();
        if p.is_dir() && !p.is_symlink() {
            let _ = std::fs::remove_dir_all(&p);
        } else {
            let _ = std::fs::remove_file(&p);
        }
    }
}

impl OutputSet {
    pub fn new() -> Self {
        install_signal_handler();
        static NEXT: AtomicU64 = AtomicU64::new(1);
        let id = NEXT.fetch_add(1, Ordering::Relaxed);
        registry().sets.insert(id, Pending::default());
        OutputSet { id, files: vec![], dirs: vec![], done: false }
    }

    /// Create a temporary and note it under the registry's lock (a Ctrl-C
    /// sees both or neither, and no file appears after its rollback).
    fn create_temp(&self, t: &Path, create: impl FnOnce() -> std::io::Result<()>) -> std::io::Result<()> {
        let mut r = registry();
        create()?;
        if let Some(p) = r.sets.get_mut(&self.id) {
            p.temps.push(t.to_path_buf());
        }
        Ok(())
    }

    /// One output path given twice (`a.vcd` and `./a.vcd` too) is an error.
    fn check_unique(&self, dest: &Path) -> Result<()> {
        let same = |d: &Path| d == dest || same_place(d, dest);
        if self.files.iter().any(|(d, _, _)| same(d)) || self.dirs.iter().any(|(d, _)| same(d)) {
            bail!("{} is given for two outputs", dest.display());
        }
        Ok(())
    }

    /// Create `dir` and its missing parents, remembering each one created.
    fn create_dirs(&self, dir: &Path) -> Result<()> {
        if dir.as_os_str().is_empty() || dir.is_dir() {
            return Ok(());
        }
        if dir.exists() {
            bail!("{} is not a directory", dir.display());
        }
        if let Some(p) = dir.parent() {
            self.create_dirs(p)?;
        }
        // Created and noted under the registry's lock: a Ctrl-C sees both or neither.
        let mut r = registry();
        match std::fs::create_dir(dir) {
            Ok(()) => {
                if let Some(p) = r.sets.get_mut(&self.id) {
                    p.created.push(dir.to_path_buf());
                }
                Ok(())
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && dir.is_dir() => Ok(()),
            Err(e) => Err(e).with_context(|| format!("cannot create directory {}", dir.display())),
        }
    }

    fn reserve(&mut self, dest: &Path) -> Result<PathBuf> {
        let name_ok = dest.file_name().is_some_and(|n| !n.is_empty());
        if !name_ok || dest.is_dir() {
            bail!("{} is a directory, not a file name", dest.display());
        }
        if let Ok(m) = std::fs::metadata(dest) {
            if !m.is_file() {
                // A device or FIFO: written directly, never replaced.
                std::fs::OpenOptions::new().write(true).open(dest).with_context(|| format!("cannot write {}", dest.display()))?;
                self.files.push((dest.to_path_buf(), dest.to_path_buf(), None));
                return Ok(dest.to_path_buf());
            }
        }
        // A symbolic link keeps pointing at the file it names, which is replaced.
        let real = if dest.is_symlink() { std::fs::canonicalize(dest).unwrap_or_else(|_| dest.to_path_buf()) } else { dest.to_path_buf() };
        if let Some(d) = real.parent().filter(|d| !d.as_os_str().is_empty()) {
            clean_stale(d);
        }
        let tmp = tmp_name(&real);
        self.create_temp(&tmp, || std::fs::write(&tmp, b"")).with_context(|| format!("cannot write {}", dest.display()))?;
        self.files.push((dest.to_path_buf(), tmp.clone(), Some(real)));
        Ok(tmp)
    }

    /// Reserve the output file `dest`: its directory must exist. Returns the
    /// temporary file to write (created empty).
    pub fn file(&mut self, dest: &Path) -> Result<PathBuf> {
        self.check_unique(dest)?;
        if let Some(d) = dest.parent().filter(|d| !d.as_os_str().is_empty()) {
            if !d.is_dir() {
                if d.exists() {
                    bail!("cannot write {}: {} is not a directory", dest.display(), d.display());
                }
                bail!("cannot write {}: directory {} does not exist", dest.display(), d.display());
            }
        }
        self.reserve(dest)
    }

    /// Reserve the output file `dest`, creating its missing directories
    /// (removed again if the set is not committed).
    pub fn file_creating_dirs(&mut self, dest: &Path) -> Result<PathBuf> {
        self.check_unique(dest)?;
        if let Some(d) = dest.parent() {
            self.create_dirs(d).with_context(|| format!("cannot write {}", dest.display()))?;
        }
        self.reserve(dest)
    }

    /// Reserve the output directory `dest` (created if missing): returns the
    /// staging directory the command fills; [`OutputSet::commit`] moves its
    /// files into `dest`.
    pub fn dir(&mut self, dest: &Path) -> Result<PathBuf> {
        self.check_unique(dest)?;
        self.root(dest).with_context(|| format!("cannot write into {}", dest.display()))?;
        let stage = dest.join(format!(".canstar.{}{TMP_SUFFIX}", pid()));
        self.create_temp(&stage, || std::fs::create_dir(&stage)).with_context(|| format!("cannot write into {}", dest.display()))?;
        self.dirs.push((dest.to_path_buf(), stage.clone()));
        Ok(stage)
    }

    /// Check an output directory whose files are reserved later
    /// ([`OutputSet::file_creating_dirs`]): it is created if missing and must
    /// be writable.
    pub fn root(&mut self, dest: &Path) -> Result<()> {
        self.create_dirs(dest)?;
        clean_stale(dest);
        let probe = dest.join(format!(".probe.{}{TMP_SUFFIX}", pid()));
        let _r = registry(); // no Ctrl-C between creating and removing it
        std::fs::write(&probe, b"").with_context(|| format!("cannot write into {}", dest.display()))?;
        let _ = std::fs::remove_file(&probe);
        Ok(())
    }

    /// The temporary file of the reserved output `dest`.
    pub fn temp_of(&self, dest: &Path) -> Option<&Path> {
        self.files.iter().find(|(d, _, _)| d == dest).map(|(_, t, _)| t.as_path())
    }

    /// Write the contents of the reserved output `dest`.
    pub fn write(&self, dest: &Path, contents: impl AsRef<[u8]>) -> Result<()> {
        let t = self.temp_of(dest).ok_or_else(|| anyhow!("{} was not reserved as an output", dest.display()))?;
        // Under the registry's lock: after a Ctrl-C's rollback no temporary reappears.
        let _r = registry();
        std::fs::write(t, contents).with_context(|| format!("writing {}", dest.display()))
    }

    /// Move every output into place (files replaced atomically one by one,
    /// the set as a whole restored to the old files if a rename fails).
    /// Returns the destinations written.
    pub fn commit(mut self) -> Result<Vec<PathBuf>> {
        // (temporary, destination) pairs, staging directories expanded.
        let mut moves: Vec<(PathBuf, PathBuf)> =
            self.files.iter().filter_map(|(_, t, real)| real.as_ref().map(|r| (t.clone(), r.clone()))).collect();
        for (dest, stage) in &self.dirs {
            let mut names: Vec<_> = std::fs::read_dir(stage)
                .with_context(|| format!("reading {}", stage.display()))?
                .flatten()
                .map(|e| e.file_name())
                .collect();
            names.sort();
            for n in names {
                let dst = dest.join(&n);
                if dst.is_dir() {
                    bail!("cannot write {}: it is a directory", dst.display());
                }
                moves.push((stage.join(&n), dst));
            }
        }
        {
            let mut r = registry();
            r.committing = true;
        }
        let result = apply(&moves);
        let interrupted = {
            let mut r = registry();
            r.committing = false;
            r.interrupted
        };
        if result.is_ok() {
            for (_, stage) in &self.dirs {
                let _ = std::fs::remove_dir_all(stage);
            }
            self.done = true;
            if let Some(p) = registry().sets.get_mut(&self.id) {
                p.temps.clear();
                // Directories created for outputs that were not produced (an
                // empty constraints folder) are not left behind.
                for d in p.created.drain(..).rev() {
                    let _ = std::fs::remove_dir(&d);
                }
            }
        }
        if interrupted {
            // Drop rolls back what is left (nothing after a successful commit).
            drop(self);
            abandon_and_exit(INTERRUPTED);
        }
        result?;
        // The files as given, then the files moved out of staging directories.
        let renamed_files = self.files.iter().filter(|f| f.2.is_some()).count();
        let mut written: Vec<PathBuf> = self.files.iter().map(|(d, _, _)| d.clone()).collect();
        written.extend(moves.into_iter().skip(renamed_files).map(|(_, d)| d));
        Ok(written)
    }
}

/// Do two paths name one place (their folders resolved, the names equal)?
fn same_place(a: &Path, b: &Path) -> bool {
    let place = |p: &Path| {
        let dir = p.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        Some((std::fs::canonicalize(dir).ok()?, p.file_name()?.to_os_string()))
    };
    matches!((place(a), place(b)), (Some(x), Some(y)) if x == y)
}

/// Rename every pair; on a failure undo the renames done (old files back,
/// new files removed) and report it.
fn apply(moves: &[(PathBuf, PathBuf)]) -> Result<()> {
    // Keep the files about to be replaced.
    let mut backups: Vec<Option<PathBuf>> = vec![];
    for (_, dest) in moves {
        if dest.is_file() {
            let b = old_name(dest);
            let _ = std::fs::remove_file(&b);
            if std::fs::hard_link(dest, &b).is_err() {
                if let Err(e) = std::fs::copy(dest, &b) {
                    remove_backups(&backups);
                    return Err(e).with_context(|| format!("cannot keep a copy of {} while replacing it", dest.display()));
                }
            }
            backups.push(Some(b));
        } else {
            backups.push(None);
        }
    }
    for (i, (tmp, dest)) in moves.iter().enumerate() {
        if let Err(e) = std::fs::rename(tmp, dest) {
            for ((_, d), b) in moves[..i].iter().zip(&backups).rev() {
                match b {
                    Some(b) => {
                        let _ = std::fs::rename(b, d);
                    }
                    None => {
                        let _ = std::fs::remove_file(d);
                    }
                }
            }
            remove_backups(&backups);
            return Err(e).with_context(|| format!("cannot write {}", dest.display()));
        }
    }
    remove_backups(&backups);
    Ok(())
}

fn remove_backups(b: &[Option<PathBuf>]) {
    for p in b.iter().flatten() {
        let _ = std::fs::remove_file(p);
    }
}

impl Drop for OutputSet {
    fn drop(&mut self) {
        let mut r = registry();
        if let Some(mut p) = r.sets.remove(&self.id) {
            if !self.done {
                p.rollback();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn listing(d: &Path) -> Vec<String> {
        let mut v = vec![];
        fn walk(d: &Path, base: &Path, v: &mut Vec<String>) {
            for e in std::fs::read_dir(d).unwrap().flatten() {
                let p = e.path();
                v.push(p.strip_prefix(base).unwrap().display().to_string());
                if p.is_dir() {
                    walk(&p, base, v);
                }
            }
        }
        walk(d, d, &mut v);
        v.sort();
        v
    }

    #[test]
    fn commit_moves_every_file_and_leaves_no_temporary() {
        let d = tempfile::tempdir().unwrap();
        let (a, b) = (d.path().join("a.txt"), d.path().join("sub/b.txt"));
        let mut s = OutputSet::new();
        s.file(&a).unwrap();
        s.file_creating_dirs(&b).unwrap();
        let stage = s.dir(&d.path().join("vcds")).unwrap();
        std::fs::write(stage.join("x.vcd"), "x").unwrap();
        s.write(&a, "A").unwrap();
        s.write(&b, "B").unwrap();
        assert!(!a.exists(), "nothing in place before the commit");
        let written = s.commit().unwrap();
        assert_eq!(written.len(), 3);
        assert_eq!(listing(d.path()), ["a.txt", "sub", "sub/b.txt", "vcds", "vcds/x.vcd"]);
        // A folder created for outputs that were not produced is removed.
        let mut s = OutputSet::new();
        s.root(&d.path().join("empty/deeper")).unwrap();
        s.commit().unwrap();
        assert!(!d.path().join("empty").exists());
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "B");
    }

    #[test]
    fn drop_without_commit_removes_temporaries_and_created_directories() {
        let d = tempfile::tempdir().unwrap();
        std::fs::write(d.path().join("keep.txt"), "old").unwrap();
        {
            let mut s = OutputSet::new();
            s.file(&d.path().join("keep.txt")).unwrap();
            s.file_creating_dirs(&d.path().join("x/y/z.v")).unwrap();
            s.dir(&d.path().join("vcds")).unwrap();
            s.root(&d.path().join("out/deep")).unwrap();
        }
        assert_eq!(listing(d.path()), ["keep.txt"]);
        assert_eq!(std::fs::read_to_string(d.path().join("keep.txt")).unwrap(), "old");
    }

    #[test]
    fn bad_destinations_are_refused_before_any_work() {
        let d = tempfile::tempdir().unwrap();
        std::fs::write(d.path().join("file"), "").unwrap();
        let mut s = OutputSet::new();
        let e = s.file(&d.path().join("no/such/x.vcd")).unwrap_err().to_string();
        assert!(e.contains("does not exist"), "{e}");
        let e = s.file(d.path()).unwrap_err().to_string();
        assert!(e.contains("is a directory"), "{e}");
        let e = s.file(&d.path().join("file/x.vcd")).unwrap_err().to_string();
        assert!(e.contains("not a directory"), "{e}");
        let e = format!("{:#}", s.dir(&d.path().join("file")).unwrap_err());
        assert!(e.contains("not a directory"), "{e}");
        s.file(&d.path().join("a")).unwrap();
        let e = s.file(&d.path().join("a")).unwrap_err().to_string();
        assert!(e.contains("two outputs"), "{e}");
        std::fs::create_dir(d.path().join("sub")).unwrap();
        let e = s.file(&d.path().join("sub/../a")).unwrap_err().to_string();
        assert!(e.contains("two outputs"), "{e}");
        drop(s);
        assert_eq!(listing(d.path()), ["file", "sub"]);
    }

    #[test]
    fn a_failing_rename_restores_the_old_set() {
        let d = tempfile::tempdir().unwrap();
        let (a, b) = (d.path().join("a"), d.path().join("b"));
        std::fs::write(&a, "old a").unwrap();
        std::fs::write(&b, "old b").unwrap();
        let mut s = OutputSet::new();
        s.file(&a).unwrap();
        s.file(&b).unwrap();
        s.write(&a, "new a").unwrap();
        s.write(&b, "new b").unwrap();
        // b's destination turns into a directory after it was reserved.
        std::fs::remove_file(&b).unwrap();
        std::fs::create_dir(&b).unwrap();
        std::fs::write(b.join("inside"), "").unwrap();
        assert!(s.commit().is_err());
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a", "a restored");
        assert_eq!(listing(d.path()), ["a", "b", "b/inside"]);
    }

    #[test]
    fn stale_temporaries_of_dead_processes_are_cleaned() {
        let d = tempfile::tempdir().unwrap();
        // pid 0 is never a user process; the name without a pid is an old-style one.
        for n in ["x.v.0.canstar-tmp", "x.canstar-tmp", "y.v.0.canstar-old"] {
            std::fs::write(d.path().join(n), "").unwrap();
        }
        std::fs::create_dir(d.path().join(".canstar.0.canstar-tmp")).unwrap();
        let mine = d.path().join(format!("z.{}.canstar-tmp", std::process::id()));
        std::fs::write(&mine, "").unwrap();
        let mut s = OutputSet::new();
        s.file(&d.path().join("out.txt")).unwrap();
        let left = listing(d.path());
        assert!(left.iter().all(|n| !n.contains(".0.canstar") && n != "x.canstar-tmp"), "{left:?}");
        assert!(mine.exists(), "a running process's temporary is kept");
    }
}
