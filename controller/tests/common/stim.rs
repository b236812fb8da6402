//! Random bus waveforms built from real frames (frame builder), with idle
//! gaps, missing ACKs, heavy stuffing, DLC 0..15 and random disturbances.
#![allow(dead_code)]

use canstar_controller::frame::{self, Frame};
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
/// standard and extended) followed by stuffing-heavy frames like those of
/// the stuffbit program.
pub fn dlc_and_stuffbit_frames() -> Vec<Frame> {
    let mut v = Vec::new();
    for dlc in 0..16u8 {
        let data: Vec<u8> = (0..8).map(|k| 0x11u8.wrapping_mul(k + dlc)).collect();
        v.push(Frame::data(false, 0x123 ^ dlc as u32, dlc, &data));
        v.push(Frame::remote(false, 0x321 ^ dlc as u32, dlc));
        v.push(Frame::data(true, 0x1234567 ^ dlc as u32, dlc, &data));
        v.push(Frame::remote(true, 0x0765432 ^ dlc as u32, dlc));
    }
    for n in 0..=8usize {
        v.push(Frame::std(0x000, &vec![0x00; n]));
        v.push(Frame::std(0x7FF, &vec![0xFF; n]));
        v.push(Frame::ext(0x0000000, &vec![0x00; n]));
        v.push(Frame::ext(0x1FFFFFFF, &vec![0xFF; n]));
        v.push(Frame::std(0x0F8, &vec![0x0F, 0x83, 0xE0, 0xF8, 0x3E, 0x0F, 0x83, 0xE0][..n]));
        v.push(Frame::ext(0x1F07C1F, &vec![0xC1, 0xF0, 0x7C, 0x1F, 0x07, 0xC1, 0xF0, 0x7C][..n]));
    }
    v
}
