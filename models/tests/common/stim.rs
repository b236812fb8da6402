//! Recorded stimulus for benchmarks: the input changes of one or more instances per
//! clock, compact (most inputs hold their value most clocks), replayable into every
//! engine (rust-hdl, compiled model, Verilator through `models/verilator/bench.cpp`).
//!
//! File format (little-endian): `CSTIM1\0\0`, u32 streams, u32 inputs, u64 cycles,
//! then per clock and per stream: u8 n, n x (u8 input index, u64 value). Values are
//! at most 64 bits wide (every port of the benchmarked designs is).

use std::io::Write;

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
