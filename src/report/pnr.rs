//! One `nextpnr-ice40` run under a watchdog, and the parsing of its log.
//!
//! nextpnr-ice40 0.4's router (router1) can livelock on some seeds: it goes on
//! printing its progress table with the same number of remaining arcs, or prints
//! nothing at all. The watchdog reads nextpnr's output as it comes (a reader
//! thread per pipe) and kills the run when it has made no progress for the stall
//! time. Progress is a new log line, except for the router's table lines, which
//! count only when the number of arcs still to route reaches a new minimum:
//!
//! ```text
//! Info:    IterCnt |  w/ripup   wo/ripup |  w/r  wo/r |      arcs| batch(sec) total(sec)|
//! Info:       1000 |       86        913 |   86   913 |      4053|       0.45       0.45|
//! ```
//!
//! nextpnr runs in a process group of its own, and the whole group is killed, so
//! that nothing it started is left running. A signal handler of the command can
//! kill the runs still going with [`kill_running`].
//!
//! nextpnr is asked for `--timing-allow-fail`, so a design that misses the
//! requested frequency still gives its achieved fmax (the log then says
//! "Warning: Max frequency ... (FAIL at 50.00 MHz)" instead of an error).

use anyhow::{Context, Result};
use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// How to run nextpnr.
#[derive(Debug, Clone)]
pub struct Pnr {
    /// The program (`nextpnr-ice40`, or a path to it).
    pub program: String,
    /// Frequency nextpnr is asked to meet, in MHz.
    pub freq_mhz: f64,
    /// Kill a run that has made no progress for this long.
    pub stall: Duration,
    /// Kill a run that has not finished after this long.
    pub timeout: Duration,
}

/// How one seed ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// Placed and routed: logic cells (ICESTORM_LC) and the achieved fmax.
    Placed { lc: usize, fmax_mhz: f64 },
    /// Killed after `stall` seconds without progress.
    Stalled { stall_s: f64 },
    /// Killed at the time limit.
    TimedOut,
    /// nextpnr ended without figures (an error, a crash).
    Failed(String),
}

/// One seed's run.
#[derive(Debug, Clone, PartialEq)]
pub struct SeedRun {
    pub seed: u64,
    pub outcome: Outcome,
    /// Wall time of the run, in seconds.
    pub secs: f64,
}

impl SeedRun {
    /// "seed 2: 53.9 MHz, 1790 LC (7.5 s)", "seed 1: stalled ...".
    pub fn describe(&self) -> String {
        let what = match &self.outcome {
            Outcome::Placed { lc, fmax_mhz } => format!("{fmax_mhz:.1} MHz, {lc} LC"),
            Outcome::Stalled { stall_s } => {
                format!("stalled: no router progress for {stall_s:.0} s, killed after {:.0} s", self.secs)
            }
            Outcome::TimedOut => format!("did not finish within {:.0} s, killed", self.secs),
            Outcome::Failed(why) => format!("failed: {why}"),
        };
        match &self.outcome {
            Outcome::Placed { .. } => format!("seed {}: {what} ({:.1} s)", self.seed, self.secs),
            _ => format!("seed {}: {what}", self.seed),
        }
    }
}

/// Placed logic cells: the "ICESTORM_LC:  1790/ 7680" line of the utilisation table.
pub fn parse_lc(log: &str) -> Option<usize> {
    log.lines().rev().filter_map(|l| l.split("ICESTORM_LC:").nth(1)).find_map(|r| r.split('/').next()?.trim().parse().ok())
}

/// The fmax after routing: the last "Max frequency for clock 'c': 53.00 MHz (PASS at
/// 50.00 MHz)" line (nextpnr prints one after placement and one after routing; the
/// last one is "Warning:" or "ERROR:" when it misses the requested frequency).
pub fn parse_fmax(log: &str) -> Option<f64> {
    log.lines()
        .rev()
        .filter_map(|l| l.split_once("Max frequency for clock ")?.1.rsplit_once("': ")?.1.split_once(" MHz"))
        .find_map(|(f, _)| f.trim().parse().ok())
}

/// The first error line of a log, without its "ERROR: " prefix.
pub fn parse_error(log: &str) -> Option<&str> {
    log.lines().find_map(|l| l.strip_prefix("ERROR: ")).map(str::trim)
}

/// A line of router1's progress table: (iterations, arcs still to route).
pub fn parse_router_line(line: &str) -> Option<(u64, u64)> {
    let l = line.strip_prefix("Info:")?;
    let f: Vec<&str> = l.split('|').collect();
    if f.len() != 6 {
        return None;
    }
    Some((f[0].trim().parse().ok()?, f[3].trim().parse().ok()?))
}

/// Decides which log lines are progress (see the module documentation).
#[derive(Debug, Default)]
pub struct Progress {
    /// Fewest arcs still to route seen so far in this routing pass.
    fewest: Option<u64>,
}

impl Progress {
    /// Does `line` show progress?
    pub fn observe(&mut self, line: &str) -> bool {
        match parse_router_line(line) {
            Some((_, left)) => {
                let better = self.fewest.is_none_or(|f| left < f);
                if better {
                    self.fewest = Some(left);
                }
                better
            }
            None => {
                if line.contains("Routing..") {
                    // A new routing pass starts from all arcs.
                    self.fewest = None;
                }
                !line.trim().is_empty()
            }
        }
    }
}

/// Process groups of the runs going on, for [`kill_running`].
static RUNNING: Mutex<Vec<u32>> = Mutex::new(Vec::new());

fn running() -> std::sync::MutexGuard<'static, Vec<u32>> {
    RUNNING.lock().unwrap_or_else(|e| e.into_inner())
}

/// Kill every nextpnr run still going (for a signal handler).
pub fn kill_running() {
    for &g in running().iter() {
        kill_group(g);
    }
}

#[cfg(unix)]
fn kill_group(pgid: u32) {
    // SAFETY: kill(2) with a negative pid signals a process group; no memory is involved.
    unsafe {
        libc::kill(-(pgid as libc::pid_t), libc::SIGKILL);
    }
}

#[cfg(not(unix))]
fn kill_group(_pgid: u32) {}

/// A child in its own process group, killed with its group when dropped early.
struct Group {
    child: Child,
    done: bool,
}

impl Group {
    fn spawn(cmd: &mut Command) -> std::io::Result<Self> {
        #[cfg(unix)]
        std::os::unix::process::CommandExt::process_group(cmd, 0);
        let child = cmd.spawn()?;
        running().push(child.id());
        Ok(Self { child, done: false })
    }
    fn kill(&mut self) {
        kill_group(self.child.id());
        let _ = self.child.kill();
    }
    fn wait(&mut self) -> std::io::Result<std::process::ExitStatus> {
        let s = self.child.wait();
        self.done = true;
        let id = self.child.id();
        running().retain(|&g| g != id);
        s
    }
}

impl Drop for Group {
    fn drop(&mut self) {
        if !self.done {
            self.kill();
            let _ = self.wait();
        }
    }
}

fn read_lines(pipe: impl Read + Send + 'static, tx: mpsc::Sender<String>) -> std::thread::JoinHandle<()> {
    std::thread::spawn(move || {
        let mut r = BufReader::new(pipe);
        let mut buf = vec![];
        loop {
            buf.clear();
            match r.read_until(b'\n', &mut buf) {
                Ok(0) | Err(_) => return,
                Ok(_) => {
                    let line = String::from_utf8_lossy(&buf).trim_end_matches(['\n', '\r']).to_string();
                    if tx.send(line).is_err() {
                        return;
                    }
                }
            }
        }
    })
}

impl Pnr {
    /// The arguments of one run (JSON netlist from `synth_ice40`).
    pub fn args(&self, json: &Path, seed: u64) -> Vec<String> {
        let mut a: Vec<String> = ["--hx8k", "--package", "cb132", "--pcf-allow-unconstrained", "--timing-allow-fail"].map(String::from).to_vec();
        a.extend(["--seed".into(), seed.to_string(), "--freq".into(), format!("{}", self.freq_mhz)]);
        a.extend(["--json".into(), json.display().to_string()]);
        a
    }

    /// Place and route `json` with one seed. An error only when nextpnr cannot be
    /// started; everything else is an [`Outcome`].
    pub fn run(&self, json: &Path, seed: u64) -> Result<SeedRun> {
        self.run_args(self.args(json, seed), seed)
    }

    /// One run with the arguments given (`canstar build` passes its PCF and
    /// output files), under the same watchdog.
    pub fn run_args(&self, args: Vec<String>, seed: u64) -> Result<SeedRun> {
        let start = Instant::now();
        let mut cmd = Command::new(&self.program);
        cmd.args(args).stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped());
        let mut g = Group::spawn(&mut cmd).with_context(|| format!("running {}", self.program))?;
        let (tx, rx) = mpsc::channel();
        let readers = [read_lines(g.child.stdout.take().unwrap(), tx.clone()), read_lines(g.child.stderr.take().unwrap(), tx)];
        let mut log = String::new();
        let mut progress = Progress::default();
        let mut last = start;
        let killed = loop {
            let now = Instant::now();
            let (stall_at, end_at) = (last + self.stall, start + self.timeout);
            if now >= end_at {
                break Some(Outcome::TimedOut);
            }
            if now >= stall_at {
                break Some(Outcome::Stalled { stall_s: self.stall.as_secs_f64() });
            }
            match rx.recv_timeout(stall_at.min(end_at) - now) {
                Ok(line) => {
                    if progress.observe(&line) {
                        last = Instant::now();
                    }
                    log.push_str(&line);
                    log.push('\n');
                }
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => break None,
            }
        };
        if killed.is_some() {
            g.kill();
        }
        let status = g.wait().with_context(|| format!("waiting for {}", self.program))?;
        let secs = start.elapsed().as_secs_f64();
        if let Some(outcome) = killed {
            // The readers end when the group's last process closes the pipes; one
            // that escaped the group would keep them, so they are not waited for.
            drop(readers);
            return Ok(SeedRun { seed, outcome, secs });
        }
        for r in readers {
            let _ = r.join();
        }
        let outcome = match (status.success(), parse_lc(&log), parse_fmax(&log)) {
            (true, Some(lc), Some(fmax_mhz)) => Outcome::Placed { lc, fmax_mhz },
            (true, _, _) => Outcome::Failed("finished without a logic-cell count or fmax in its log".into()),
            (false, _, _) => Outcome::Failed(match parse_error(&log) {
                Some(e) => e.to_string(),
                None => format!("{} ({status})", self.program),
            }),
        };
        Ok(SeedRun { seed, outcome, secs })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::fake::{alive, fake, SILENT};

    /// Excerpts of a real nextpnr-ice40 0.4-1 log (canstar_crc15 in its measurement
    /// wrapper, `--freq 50`, seed 1): it routes and meets the frequency.
    const ROUTED: &str = "\
Info: Device utilisation:
Info: \t         ICESTORM_LC:    49/ 7680     0%
Info: \t        ICESTORM_RAM:     0/   32     0%
Info: \t               SB_IO:     3/  256     1%
Info: Max frequency for clock 'clock$SB_IO_IN_$glb_clk': 283.45 MHz (PASS at 50.00 MHz)
Info: Routing..
Info: Setting up routing queue.
Info: Routing 85 arcs.
Info:            |   (re-)routed arcs  |   delta    | remaining|       time spent     |
Info:    IterCnt |  w/ripup   wo/ripup |  w/r  wo/r |      arcs| batch(sec) total(sec)|
Info:         88 |        3         85 |    3    85 |         0|       0.02       0.02|
Info: Routing complete.
Info: Max frequency for clock 'clock$SB_IO_IN_$glb_clk': 235.52 MHz (PASS at 50.00 MHz)

Info: Max delay <async>                         -> posedge clock$SB_IO_IN_$glb_clk: 1.75 ns
1 warning, 0 errors

Info: Program finished normally.
";

    /// The same design asked for 400 MHz without `--timing-allow-fail`: exit status 1.
    const FAILED: &str = "\
Info: \t         ICESTORM_LC:    49/ 7680     0%
Info: Max frequency for clock 'clock$SB_IO_IN_$glb_clk': 283.45 MHz (FAIL at 400.00 MHz)
Info: Routing complete.
ERROR: Max frequency for clock 'clock$SB_IO_IN_$glb_clk': 235.52 MHz (FAIL at 400.00 MHz)
1 warning, 1 error
";

    /// ... and with `--timing-allow-fail`: a warning, exit status 0.
    const ALLOWED: &str = "\
Info: \t         ICESTORM_LC:    49/ 7680     0%
Info: Max frequency for clock 'clock$SB_IO_IN_$glb_clk': 283.45 MHz (FAIL at 400.00 MHz)
Info: Routing complete.
Warning: Max frequency for clock 'clock$SB_IO_IN_$glb_clk': 235.52 MHz (FAIL at 400.00 MHz)
2 warnings, 0 errors
";

    /// Router table of canstar_can_core (real log, seed 1).
    const ROUTER: &str = "\
Info: Routing 4914 arcs.
Info:            |   (re-)routed arcs  |   delta    | remaining|       time spent     |
Info:    IterCnt |  w/ripup   wo/ripup |  w/r  wo/r |      arcs| batch(sec) total(sec)|
Info:       1000 |       86        913 |   86   913 |      4053|       0.45       0.45|
Info:       2000 |      305       1673 |  219   760 |      3345|       0.12       0.57|
Info:       6810 |     1445       5246 |   55   756 |         0|       0.26       1.38|
";

    #[test]
    fn parses_a_routed_log() {
        assert_eq!(parse_lc(ROUTED), Some(49));
        // The post-route figure, not the post-placement estimate.
        assert_eq!(parse_fmax(ROUTED), Some(235.52));
        assert_eq!(parse_error(ROUTED), None);
    }

    #[test]
    fn parses_a_log_that_misses_the_frequency() {
        for log in [FAILED, ALLOWED] {
            assert_eq!(parse_lc(log), Some(49));
            assert_eq!(parse_fmax(log), Some(235.52));
        }
        assert_eq!(parse_error(FAILED), Some("Max frequency for clock 'clock$SB_IO_IN_$glb_clk': 235.52 MHz (FAIL at 400.00 MHz)"));
        assert_eq!(parse_error(ALLOWED), None);
        assert_eq!(parse_fmax("Info: Routing complete.\n"), None);
        assert_eq!(parse_lc("Info: ICESTORM_RAM:     0/   32\n"), None);
    }

    #[test]
    fn parses_the_router_table() {
        let rows: Vec<_> = ROUTER.lines().filter_map(parse_router_line).collect();
        assert_eq!(rows, vec![(1000, 4053), (2000, 3345), (6810, 0)]);
    }

    #[test]
    fn progress_is_a_new_line_or_fewer_arcs_left() {
        let mut p = Progress::default();
        assert!(p.observe("Info: Routing.."));
        let line = |left: u64| format!("Info:       1000 |       86        913 |   86   913 |      {left}|       0.45       0.45|");
        assert!(p.observe(&line(4053)));
        assert!(p.observe(&line(3345)));
        // A livelock: the router goes round the same numbers.
        assert!(!p.observe(&line(3345)));
        assert!(!p.observe(&line(3400)));
        assert!(!p.observe(&line(3345)));
        assert!(p.observe(&line(3344)));
        assert!(!p.observe(""));
        // A second routing pass starts afresh.
        assert!(p.observe("Info: Routing.."));
        assert!(p.observe(&line(4000)));
    }

    #[test]
    fn asks_for_timing_allow_fail_and_the_seed() {
        let p = Pnr { program: "nextpnr-ice40".into(), freq_mhz: 50.0, stall: Duration::from_secs(1), timeout: Duration::from_secs(1) };
        let a = p.args(Path::new("/x/w.json"), 7).join(" ");
        assert!(a.contains("--timing-allow-fail") && a.contains("--seed 7") && a.contains("--freq 50 ") && a.contains("--json /x/w.json"), "{a}");
    }

    /// The same router line again and again, as a livelocked router prints it.
    const REPEATING: &str = "echo 'Info: Routing..' >&2\nwhile true; do\n\
echo 'Info:       1000 |       86        913 |   86   913 |      4053|       0.45       0.45|' >&2\nsleep 0.1\ndone\n";

    fn pnr(program: String, stall_s: u64, timeout_s: u64) -> Pnr {
        Pnr { program, freq_mhz: 50.0, stall: Duration::from_secs(stall_s), timeout: Duration::from_secs(timeout_s) }
    }

    #[test]
    fn watchdog_kills_a_silent_run_and_its_children() {
        let d = tempfile::tempdir().unwrap();
        let r = pnr(fake(d.path(), SILENT), 2, 60).run(Path::new("x.json"), 1).unwrap();
        assert_eq!(r.outcome, Outcome::Stalled { stall_s: 2.0 });
        assert!((2.0..10.0).contains(&r.secs), "{r:?}");
        assert_eq!(std::fs::read_to_string(d.path().join("pids")).unwrap().lines().count(), 2);
        assert!(alive(d.path()).is_empty(), "left running: {:?}", alive(d.path()));
        assert!(r.describe().starts_with("seed 1: stalled: no router progress for 2 s"), "{}", r.describe());
    }

    #[test]
    fn watchdog_kills_a_router_that_repeats_itself() {
        let d = tempfile::tempdir().unwrap();
        let r = pnr(fake(d.path(), REPEATING), 2, 60).run(Path::new("x.json"), 3).unwrap();
        assert_eq!(r.outcome, Outcome::Stalled { stall_s: 2.0 });
        assert!((2.0..10.0).contains(&r.secs), "{r:?}");
        assert!(alive(d.path()).is_empty(), "left running: {:?}", alive(d.path()));
    }

    #[test]
    fn time_limit_stops_a_run_that_keeps_progressing() {
        let d = tempfile::tempdir().unwrap();
        let body = "i=0\nwhile true; do i=$((i+1)); echo \"Info: placer iter $i\" >&2; sleep 0.1; done\n";
        let r = pnr(fake(d.path(), body), 2, 3).run(Path::new("x.json"), 1).unwrap();
        assert_eq!(r.outcome, Outcome::TimedOut);
        assert!((3.0..10.0).contains(&r.secs), "{r:?}");
        assert!(alive(d.path()).is_empty());
    }

    #[test]
    fn a_finished_run_gives_its_figures_or_its_error() {
        let d = tempfile::tempdir().unwrap();
        std::fs::write(d.path().join("routed.log"), ROUTED).unwrap();
        std::fs::write(d.path().join("failed.log"), FAILED).unwrap();
        let ok = pnr(fake(d.path(), "cat \"$(dirname \"$0\")/routed.log\" >&2\n"), 5, 60);
        assert_eq!(ok.run(Path::new("x.json"), 1).unwrap().outcome, Outcome::Placed { lc: 49, fmax_mhz: 235.52 });
        let bad = pnr(fake(d.path(), "cat \"$(dirname \"$0\")/failed.log\" >&2\nexit 1\n"), 5, 60);
        let r = bad.run(Path::new("x.json"), 2).unwrap();
        assert!(matches!(&r.outcome, Outcome::Failed(e) if e.contains("FAIL at 400.00 MHz")), "{r:?}");
        let crash = pnr(fake(d.path(), "exit 3\n"), 5, 60);
        assert!(matches!(crash.run(Path::new("x.json"), 2).unwrap().outcome, Outcome::Failed(e) if e.contains("exit status: 3")));
        assert!(pnr(d.path().join("absent").display().to_string(), 5, 60).run(Path::new("x.json"), 1).is_err());
    }
}
