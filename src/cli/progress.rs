//! Progress of long runs (network simulation, fuzz, campaigns) with an
//! estimate of the time left: a bar on a terminal; otherwise (a log file, a
//! pipe, CI) one plain line at every tenth of the work, so logs stay short.

use std::time::Instant;

pub struct Progress {
    bar: indicatif::ProgressBar,
    t0: Instant,
    len: u64,
    unit: &'static str,
    /// Tenths of the work reported so far (plain mode).
    tenths: u64,
    msg: String,
}

impl Progress {
    /// Work of `len` units (`"runs"`, `"frames"`, `"us simulated"`).
    pub fn new(len: u64, unit: &'static str) -> Self {
        let bar = indicatif::ProgressBar::new(len);
        let template = format!("{{elapsed_precise}} [{{bar:40}}] {{pos}}/{{len}} {unit} ({{per_sec}}, eta {{eta}}) {{msg}}");
        if let Ok(style) = indicatif::ProgressStyle::with_template(&template) {
            bar.set_style(style.progress_chars("=> "));
        }
        Progress { bar, t0: Instant::now(), len: len.max(1), unit, tenths: 0, msg: String::new() }
    }

    /// Is the bar drawn (standard error is a terminal)?
    pub fn is_drawn(&self) -> bool {
        !self.bar.is_hidden()
    }

    /// Move to `pos` units done.
    pub fn set(&mut self, pos: u64) {
        self.bar.set_position(pos);
        let pos = pos.min(self.len);
        let tenths = pos * 10 / self.len;
        let dt = self.t0.elapsed().as_secs_f64();
        // Plain lines only for runs longer than a second.
        if !self.is_drawn() && tenths > self.tenths && pos < self.len && dt >= 1.0 {
            self.tenths = tenths;
            let left = dt * (self.len - pos) as f64 / pos.max(1) as f64;
            let msg = if self.msg.is_empty() { String::new() } else { format!(", {}", self.msg) };
            errln!("{dt:.0} s: {pos}/{} {} ({}0 %), about {left:.0} s left{msg}", self.len, self.unit, tenths);
        }
    }

    /// Advance by one unit.
    pub fn inc(&mut self) {
        let p = self.bar.position() + 1;
        self.set(p);
    }

    /// A short status shown beside the bar (and on the plain lines).
    pub fn set_message(&mut self, m: String) {
        self.bar.set_message(m.clone());
        self.msg = m;
    }

    /// Print around the bar.
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        self.bar.suspend(f)
    }

    /// Remove the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
