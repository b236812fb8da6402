//! Test helpers shared by the equivalence tests: port indices by name and a CAN
//! node's host (requests, aborts, mode changes, counter loads, recovery).
#![allow(dead_code)]

pub mod hubnet;
pub mod sjanet;
#[allow(unused_imports)]
pub use canstar_models::stim;

use canstar_rtlc::rt::Model;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Port indices by name.
pub struct Ports {
    pub ins: Vec<&'static str>,
    pub outs: Vec<&'static str>,
}

impl Ports {
    pub fn of(m: &dyn Model) -> Ports {
        let i = m.info();
        Ports { ins: i.inputs.iter().map(|p| p.name).collect(), outs: i.outputs.iter().map(|p| p.name).collect() }
    }
    pub fn i(&self, n: &str) -> usize {
        self.ins.iter().position(|x| *x == n).unwrap_or_else(|| panic!("no input {n}"))
    }
    pub fn o(&self, n: &str) -> usize {
        self.outs.iter().position(|x| *x == n).unwrap_or_else(|| panic!("no output {n}"))
    }
}

/// The host side of one node: requests, aborts, mode changes, counter loads.
pub struct Host {
    pub v: Vec<u128>,
    busy: bool,
    low: u32,
}

impl Host {
    pub fn new(p: &Ports, timing: (u128, u128, u128, u128), triple: bool) -> Host {
        let mut v = vec![0u128; p.ins.len()];
        v[p.i("brp")] = timing.0;
        v[p.i("prop")] = timing.1;
        v[p.i("ph1")] = timing.2;
        v[p.i("ph2")] = timing.2.max(1);
        v[p.i("sjw")] = timing.3;
        v[p.i("triple")] = triple as u128;
        v[p.i("reset")] = 1;
        v[p.i("rx")] = 1;
        Host { v, busy: false, low: 0 }
    }

    pub fn tick(&mut self, p: &Ports, out: &[u128], rng: &mut ChaCha8Rng, cycle: u64) {
        let v = &mut self.v;
        v[p.i("reset")] = (cycle < 3 || rng.gen_bool(0.000_01)) as u128;
        v[p.i("recover")] = 0;
        v[p.i("tx_abort")] = 0;
        v[p.i("cnt_load")] = 0;
        let done = out[p.o("tx_done")] != 0;
        let single = v[p.i("single_shot")] != 0;
        let failed = single && (out[p.o("arb_lost")] != 0 || (out[p.o("error")] != 0 && out[p.o("err_tx")] != 0));
        if self.busy && (done || failed || rng.gen_bool(0.000_02)) {
            self.busy = false;
            v[p.i("tx_req")] = 0;
            self.low = rng.gen_range(1..400);
        } else if !self.busy {
            if self.low > 0 {
                self.low -= 1;
            } else if rng.gen_bool(0.002) {
                self.busy = true;
                v[p.i("tx_req")] = 1;
                v[p.i("tx_ide")] = rng.gen_bool(0.4) as u128;
                v[p.i("tx_rtr")] = rng.gen_bool(0.1) as u128;
                v[p.i("tx_id")] = rng.gen::<u32>() as u128 & 0x1fff_ffff;
                v[p.i("tx_dlc")] = rng.gen_range(0..16);
                v[p.i("tx_data")] = rng.gen::<u64>() as u128;
            }
        }
        if self.busy && rng.gen_bool(0.000_05) {
            v[p.i("tx_abort")] = 1;
        }
        if rng.gen_bool(0.000_02) {
            // a mode change
            let k = rng.gen_range(0..4);
            let name = ["listen_only", "self_test", "single_shot", "host_recovery"][k];
            v[p.i(name)] = rng.gen_bool(if k == 0 { 0.2 } else { 0.5 }) as u128;
        }
        if out[p.o("state")] == 2 && rng.gen_bool(0.001) {
            v[p.i("recover")] = 1;
        }
        if rng.gen_bool(0.000_01) {
            v[p.i("cnt_load")] = 1;
            v[p.i("tec_in")] = rng.gen_range(0..300);
            v[p.i("rec_in")] = rng.gen_range(0..256);
        }
    }
}

