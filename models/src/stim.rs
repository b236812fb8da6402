//! Recorded stimulus for benchmarks: the input changes of one or more instances per
//! clock, compact (most inputs hold their value most clocks), replayable into every
//! engine (rust-hdl, compiled model, Verilator through `models/verilator/bench.cpp`),
//! and the replay loops that time each engine on it (per CPU second of the thread).
//!
//! File format (little-endian): `CSTIM1\0\0`, u32 streams, u32 inputs, u64 cycles,
//! then per clock and per stream: u8 n, n x (u8 input index, u64 value). Values are
//! at most 64 bits wide (every port of the benchmarked designs is).

use std::io::Write;

use canstar_hdl::drive;
use canstar_rtlc::rt::Model;

#[derive(Clone)]
pub struct Stim {
    pub streams: usize,
    pub inputs: usize,
    pub cycles: u64,
    pub data: Vec<u8>,
    last: Vec<Vec<u64>>,
}

impl Stim {
    pub fn new(streams: usize, inputs: usize) -> Stim {
        assert!(inputs < 256);
        Stim { streams, inputs, cycles: 0, data: vec![], last: vec![vec![u64::MAX; inputs]; streams] }
    }

    /// Record stream `k`'s input vector of this clock (streams in order, then `next`).
    pub fn push(&mut self, k: usize, v: &[u128]) {
        let changed: Vec<usize> = (0..self.inputs).filter(|&i| v[i] as u64 != self.last[k][i]).collect();
        self.data.push(changed.len() as u8);
        for i in changed {
            let x = v[i] as u64;
            assert_eq!(x as u128, v[i], "input wider than 64 bits");
            self.data.push(i as u8);
            self.data.extend_from_slice(&x.to_le_bytes());
            self.last[k][i] = x;
        }
    }

    pub fn next(&mut self) {
        self.cycles += 1;
    }

    /// One multi-stream stimulus from single-stream ones of the same design (streams
    /// in order; as many clocks as the shortest).
    pub fn merge(parts: &[Stim]) -> Stim {
        assert!(!parts.is_empty() && parts.iter().all(|p| p.streams == 1 && p.inputs == parts[0].inputs));
        let cycles = parts.iter().map(|p| p.cycles).min().unwrap();
        let mut vs: Vec<Vec<Vec<u128>>> = vec![];
        for p in parts {
            let mut v = vec![0u128; p.inputs];
            let mut rows = Vec::with_capacity(cycles as usize);
            p.replay(|c, _, ch| {
                if c < cycles {
                    for (i, x) in ch {
                        v[i] = x as u128;
                    }
                    rows.push(v.clone());
                }
            });
            vs.push(rows);
        }
        let mut s = Stim::new(parts.len(), parts[0].inputs);
        for c in 0..cycles as usize {
            for (k, rows) in vs.iter().enumerate() {
                s.push(k, &rows[c]);
            }
            s.next();
        }
        s
    }

    /// The first `cycles` clocks.
    pub fn head(&self, cycles: u64) -> Stim {
        let mut s = Stim::new(self.streams, self.inputs);
        let mut v = vec![vec![0u128; self.inputs]; self.streams];
        self.replay(|c, k, ch| {
            if c < cycles {
                for (i, x) in ch {
                    v[k][i] = x as u128;
                }
                s.push(k, &v[k]);
                if k + 1 == self.streams {
                    s.next();
                }
            }
        });
        s
    }

    /// Replay: `f(cycle, stream, changes)` with (input index, value) pairs.
    pub fn replay(&self, mut f: impl FnMut(u64, usize, &mut dyn Iterator<Item = (usize, u64)>)) {
        let mut p = 0;
        for c in 0..self.cycles {
            for k in 0..self.streams {
                let n = self.data[p] as usize;
                p += 1;
                let start = p;
                p += n * 9;
                let d = &self.data[start..p];
                let mut it = (0..n).map(|j| (d[j * 9] as usize, u64::from_le_bytes(d[j * 9 + 1..j * 9 + 9].try_into().unwrap())));
                f(c, k, &mut it);
            }
        }
    }

    pub fn save(&self, path: &std::path::Path) -> std::io::Result<()> {
        let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
        f.write_all(b"CSTIM1\0\0")?;
        f.write_all(&(self.streams as u32).to_le_bytes())?;
        f.write_all(&(self.inputs as u32).to_le_bytes())?;
        f.write_all(&self.cycles.to_le_bytes())?;
        f.write_all(&self.data)?;
        Ok(())
    }
}

/// FNV-1a over output vectors (low 64 bits of each output), the check value the
/// Verilator harness computes too.
pub struct OutHash(pub u64);

impl OutHash {
    pub fn new() -> OutHash {
        OutHash(0xcbf2_9ce4_8422_2325)
    }
    pub fn add(&mut self, o: &[u128]) {
        for &x in o {
            for b in (x as u64).to_le_bytes() {
                self.0 ^= b as u64;
                self.0 = self.0.wrapping_mul(0x100_0000_01b3);
            }
        }
    }
}

impl Default for OutHash {
    fn default() -> Self {
        Self::new()
    }
}

/// CPU time of this thread in seconds (the machine may be shared: wall time would
/// count other processes' time slices).
pub fn cpu() -> f64 {
    let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes the timespec it is given.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// Replay into compiled models (one per stream, from `fresh`): (CPU seconds, output
/// hash when `hash`).
pub fn replay_model<M: Model>(fresh: impl Fn() -> M, st: &Stim, hash: bool) -> (f64, u64) {
    let mut ms: Vec<M> = (0..st.streams).map(|_| fresh()).collect();
    let mut out = vec![0u128; ms[0].info().outputs.len()];
    let mut h = OutHash::new();
    let t = cpu();
    st.replay(|_, k, ch| {
        let m = &mut ms[k];
        for (i, v) in ch {
            m.set_input(i, v as u128);
        }
        m.cycle();
        if hash {
            m.outputs(&mut out);
            h.add(&out);
        }
    });
    (cpu() - t, h.0)
}

/// Replay into rust-hdl instances (from `fresh`, then `drive::init`) through the
/// generated port adapters `set`/`get`: (CPU seconds, output hash).
pub fn replay_hdl<H: drive::Clocked>(fresh: impl Fn() -> H, set: fn(&mut H, &[u128]), get: fn(&H, &mut [u128]), n_out: usize, st: &Stim) -> (f64, u64) {
    let mut hs: Vec<H> = (0..st.streams)
        .map(|_| {
            let mut h = fresh();
            drive::init(&mut h);
            h
        })
        .collect();
    let mut vs = vec![vec![0u128; st.inputs]; st.streams];
    let mut out = vec![0u128; n_out];
    let mut hash = OutHash::new();
    let t = cpu();
    st.replay(|_, k, ch| {
        for (i, v) in ch {
            vs[k][i] = v as u128;
        }
        set(&mut hs[k], &vs[k]);
        drive::cycle(&mut hs[k]);
        get(&hs[k], &mut out);
        hash.add(&out);
    });
    (cpu() - t, hash.0)
}

/// Verilator's mangling of a port name (`rx$0` -> `rx__0240`).
pub fn verilator_name(n: &str) -> String {
    n.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c.to_string() } else { format!("__0{:02x}", c as u32) }).collect()
}

/// C++ port adapters of a model's top for `models/verilator/bench.cpp` (`ports.h`):
/// `set_input(top, i, v)` and `get_outputs(top, o)` in the model's port order.
pub fn verilator_ports_h(m: &dyn Model) -> String {
    let info = m.info();
    let mut s = String::from("// Generated by canstar_models::stim::verilator_ports_h: port adapters.\n");
    s += &format!("static const int N_IN = {};\nstatic const int N_OUT = {};\n", info.inputs.len(), info.outputs.len());
    s += "static inline void set_input(BENCH_TOP* t, int i, uint64_t v) {\n    switch (i) {\n";
    for (i, p) in info.inputs.iter().enumerate() {
        s += &format!("    case {i}: t->{} = v; break;\n", verilator_name(p.name));
    }
    s += "    }\n}\nstatic inline void get_outputs(BENCH_TOP* t, uint64_t* o) {\n";
    for (i, p) in info.outputs.iter().enumerate() {
        s += &format!("    o[{i}] = t->{};\n", verilator_name(p.name));
    }
    s += "}\n";
    s
}

/// The Verilator harness source (`models/verilator/bench.cpp`).
pub const VERILATOR_BENCH_CPP: &str = include_str!("../verilator/bench.cpp");
