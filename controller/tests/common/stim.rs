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
