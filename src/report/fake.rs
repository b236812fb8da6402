//! A fake `nextpnr-ice40` for the watchdog tests: a shell script in a temporary
//! folder that appends the pids of its processes to `pids` there.

use std::path::Path;

/// Write the fake with `body` after its first line; returns its path.
pub fn fake(dir: &Path, body: &str) -> String {
    use std::os::unix::fs::PermissionsExt;
    let p = dir.join("nextpnr-ice40");
    std::fs::write(&p, format!("#!/bin/sh\necho $$ >> \"$(dirname \"$0\")/pids\"\n{body}")).unwrap();
    std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o755)).unwrap();
    p.display().to_string()
}

/// Pids written by the fake that are still running (a zombie is not).
pub fn alive(dir: &Path) -> Vec<String> {
    let pids = std::fs::read_to_string(dir.join("pids")).unwrap_or_default();
    pids.split_whitespace()
        .filter(|p| {
            std::fs::read_to_string(format!("/proc/{p}/stat"))
                .is_ok_and(|s| s.rsplit_once(')').is_some_and(|(_, r)| !r.trim_start().starts_with(['Z', 'X'])))
        })
        .map(String::from)
        .collect()
}

/// Router lines, then a child process that sleeps: no line for an hour.
pub const SILENT: &str = "echo 'Info: Routing..' >&2
echo 'Info:       1000 |       86        913 |   86   913 |      4053|       0.45       0.45|' >&2
sleep 3600 &
echo $! >> \"$(dirname \"$0\")/pids\"
wait
";
