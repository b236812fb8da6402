//! A fake `nextpnr-ice40` for the watchdog tests: a shell script in a temporary
//! folder that appends the pids of its processes to `pids` there. Test support,
//! shared by the unit tests and `tests/report_cli.rs` (hence public, hidden from
//! the documentation).

use std::path::Path;

/// Write the fake with `body` after its first line; returns its path.
pub fn fake(dir: &Path, body: &str) -> String {
    use std::os::unix::fs::PermissionsExt;
    let p = dir.join("nextpnr-ice40");
    std::fs::write(&p, format!("#!/bin/sh\necho $$ >> \"$(dirname \"$0\")/pids\"\n{body}")).unwrap();
    std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o755)).unwrap();
    p.display().to_string()
}

/// Pids written by the fake that are still running (a zombie is not), after
/// waiting up to 5 s for them to go: a killed process is reaped by the kernel a
/// moment after the kill returns, longer when the machine is loaded.
pub fn alive(dir: &Path) -> Vec<String> {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(5);
    loop {
        let pids = std::fs::read_to_string(dir.join("pids")).unwrap_or_default();
        let left: Vec<String> = pids
            .split_whitespace()
            .filter(|p| {
                std::fs::read_to_string(format!("/proc/{p}/stat"))
                    .is_ok_and(|s| s.rsplit_once(')').is_some_and(|(_, r)| !r.trim_start().starts_with(['Z', 'X'])))
            })
            .map(String::from)
            .collect();
        if left.is_empty() || std::time::Instant::now() > deadline {
            return left;
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

/// Router lines, then a child process that sleeps: no line for an hour.
pub const SILENT: &str = "echo 'Info: Routing..' >&2
echo 'Info:       1000 |       86        913 |   86   913 |      4053|       0.45       0.45|' >&2
sleep 3600 &
echo $! >> \"$(dirname \"$0\")/pids\"
wait
";
