//! Random bus waveforms built from real frames (frame builder), with idle
//! gaps, missing ACKs, heavy stuffing, DLC 0..15 and random disturbances.
#![allow(dead_code)]

use canstar_controller::frame::{self, bus_bits, stuff_cases, BuildOptions, Frame, StuffCase};
use rand::SeedableRng;
use std::collections::BTreeSet;
use rand::Rng;
use std::collections::VecDeque;

/// A random frame biased towards the interesting cases.
pub fn random_frame<R: Rng>(rng: &mut R) -> Frame {
    let ide = rng.gen_bool(0.5);
    let id = match rng.gen_range(0..4) {
        0 => 0,
        1 => if ide { 0x1FFF_FFFF } else { 0x7FF },
        _ => rng.gen::<u32>() & if ide { 0x1FFF_FFFF } else { 0x7FF },
    };
    let dlc = rng.gen_range(0..16u8);
    if rng.gen_bool(0.15) {
        return Frame::remote(ide, id, dlc);
    }
    let fill: u8 = match rng.gen_range(0..4) {
        0 => 0x00,
        1 => 0xFF,
        2 => 0x0F,
        _ => rng.gen(),
    };
    let data: Vec<u8> = (0..8).map(|_| if rng.gen_bool(0.7) { fill } else { rng.gen() }).collect();
    Frame::data(ide, id, dlc, &data)
}

/// Level generator: one call per bit.
pub struct BusScript {
    q: VecDeque<bool>,
    pub disturb: f64,
}

impl BusScript {
    pub fn new(disturb: f64) -> Self {
        BusScript { q: VecDeque::new(), disturb }
    }
    /// Queue these frames (acknowledged, 3 idle bits after each) before the
    /// random ones.
    pub fn push_frames(&mut self, frames: &[Frame]) {
        for f in frames {
            self.q.extend(std::iter::repeat_n(true, 4));
            self.q.extend(frame::bus_levels(f, true));
            self.q.extend(std::iter::repeat_n(true, 3));
        }
    }
    /// Queue frames built with the given options (scripted transmitters).
    pub fn push_frames_with(&mut self, frames: &[(Frame, BuildOptions)]) {
        for (f, o) in frames {
            self.q.extend(std::iter::repeat_n(true, 4));
            self.q.extend(bus_bits(f, *o, true).iter().map(|b| b.level));
            self.q.extend(std::iter::repeat_n(true, 3));
        }
    }
    /// Queue `n` recessive bits.
    pub fn push_idle(&mut self, n: usize) {
        self.q.extend(std::iter::repeat_n(true, n));
    }
    /// Bits still queued.
    pub fn queued(&self) -> usize {
        self.q.len()
    }
    pub fn next_bit<R: Rng>(&mut self, rng: &mut R) -> bool {
        if self.q.is_empty() {
            for _ in 0..rng.gen_range(0..14) {
                self.q.push_back(true);
            }
            let f = random_frame(rng);
            let acked = rng.gen_bool(0.85);
            self.q.extend(frame::bus_levels(&f, acked));
            for _ in 0..3 {
                self.q.push_back(true);
            }
            if rng.gen_bool(0.05) {
                // a dominant burst (error/overload flags of other nodes)
                for _ in 0..rng.gen_range(1..14) {
                    self.q.push_back(false);
                }
            }
        }
        let b = self.q.pop_front().unwrap();
        if rng.gen_bool(self.disturb) {
            !b
        } else {
            b
        }
    }
}

/// The frames of the dlc conformance program (data and remote, DLC 0..15,
/// standard and extended) followed by the stuffbit program frames (chosen for
/// stuffing coverage, receiver frames with all reserved-bit variants), each
/// with the options to build it.
pub fn dlc_and_stuffbit_frames() -> Vec<(Frame, BuildOptions)> {
    let d = BuildOptions::default();
    let mut v = Vec::new();
    for dlc in 0..16u8 {
        let data: Vec<u8> = (0..8).map(|k| 0x11u8.wrapping_mul(k + dlc)).collect();
        v.push((Frame::data(false, 0x123 ^ dlc as u32, dlc, &data), d));
        v.push((Frame::remote(false, 0x321 ^ dlc as u32, dlc), d));
        v.push((Frame::data(true, 0x1234567 ^ dlc as u32, dlc, &data), d));
        v.push((Frame::remote(true, 0x0765432 ^ dlc as u32, dlc), d));
    }
    v.extend(choose_stuffbit(11, &STUFFBIT_RX_OPTIONS, 1).0);
    v.extend(choose_stuffbit(8, &[d], 2).0);
    v
}

/// The reserved-bit variants of the stuffbit receiver frames.
pub const STUFFBIT_RX_OPTIONS: [BuildOptions; 4] = [
    BuildOptions { srr: true, r1: false, r0: false },
    BuildOptions { srr: true, r1: false, r0: true },
    BuildOptions { srr: true, r1: true, r0: false },
    BuildOptions { srr: true, r1: true, r0: true },
];

pub fn stuff_cases_of(f: &Frame, o: BuildOptions) -> BTreeSet<StuffCase> {
    stuff_cases(&bus_bits(f, o, true))
}

/// Greedy choice of at least `n` frames (from seeded random candidates),
/// continued until every case reachable by the candidates is covered.
pub fn choose_stuffbit(n: usize, options: &[BuildOptions], seed: u64) -> (Vec<(Frame, BuildOptions)>, BTreeSet<StuffCase>, BTreeSet<StuffCase>) {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let cands: Vec<(Frame, BuildOptions)> = (0..6000)
        .map(|k| (random_frame(&mut rng), options[k % options.len()]))
        .collect();
    let all: BTreeSet<StuffCase> = cands.iter().flat_map(|(f, o)| stuff_cases_of(f, *o)).collect();
    let mut covered = BTreeSet::new();
    let mut chosen = Vec::new();
    // make sure every option appears
    for o in options {
        let (f, _) = cands.iter().filter(|(_, oo)| oo == o).max_by_key(|(f, o)| stuff_cases_of(f, *o).len()).unwrap();
        covered.extend(stuff_cases_of(f, *o));
        chosen.push((f.clone(), *o));
    }
    while chosen.len() < n || covered.len() < all.len() {
        let best = cands.iter().max_by_key(|(f, o)| stuff_cases_of(f, *o).difference(&covered).count()).unwrap();
        covered.extend(stuff_cases_of(&best.0, best.1));
        chosen.push(best.clone());
    }
    (chosen, covered, all)
}

