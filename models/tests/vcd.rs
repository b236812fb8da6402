//! VCD compatibility: a compiled model presents its signals through rust-hdl's
//! `Probe` interface with the hierarchy, names, types and values of the rust-hdl
//! instance, so a VCD written from it (here with rust-hdl's own VCD writer; canstar's
//! writer walks the same interface) is byte-identical to one written from rust-hdl.

mod common;

use canstar_hdl::drive::{self, Clocked};
use canstar_models::generated as g;
use canstar_rtlc::rt::{AsBlock, Block, Model};
use rust_hdl::core::prelude::{write_vcd_change, write_vcd_header};

/// Both engines on the same inputs for `cycles` clocks, one VCD each.
fn vcds<H: Clocked, M: Model>(mut h: H, make: fn(&dyn Block) -> Result<M, canstar_rtlc::Error>, set: fn(&mut H, &[u128]), stim: &mut dyn FnMut(u64, &[u128]) -> Vec<u128>, get: fn(&H, &mut [u128]), cycles: u64) -> (Vec<u8>, Vec<u8>) {
    drive::init(&mut h);
    let mut m = make(&h).unwrap();
    m.set_trace(true);
    let (mut a, mut b) = (vec![], vec![]);
    {
        let mut va = write_vcd_header(&mut a, &h);
        let mut vb = write_vcd_header(&mut b, &AsBlock(&m));
        let mut out = vec![0u128; m.info().outputs.len()];
        for c in 0..cycles {
            get(&h, &mut out);
            let v = stim(c, &out);
            set(&mut h, &v);
            drive::cycle(&mut h);
            m.set_inputs(&v);
            m.cycle();
            va.timestamp(c * 1000).unwrap();
            vb.timestamp(c * 1000).unwrap();
            va = write_vcd_change(va, &h);
            vb = write_vcd_change(vb, &AsBlock(&m));
        }
    }
    (a, b)
}

fn same(what: &str, a: &[u8], b: &[u8]) {
    assert!(a.len() > 10_000, "{what}: a VCD of only {} bytes", a.len());
    if a != b {
        let (ta, tb) = (String::from_utf8_lossy(a), String::from_utf8_lossy(b));
        let line = ta.lines().zip(tb.lines()).position(|(x, y)| x != y).unwrap_or(0);
        panic!("{what}: VCDs differ at line {line}: rust-hdl `{}`, model `{}`", ta.lines().nth(line).unwrap_or(""), tb.lines().nth(line).unwrap_or(""));
    }
}

#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn can_core_vcd_is_byte_identical() {
    let p = common::Ports::of(&g::can_core::CanCore::new());
    let mut host = common::Host::new(&p, (0, 0, 3, 3), false);
    let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(3);
    let mut stim = |c: u64, out: &[u128]| {
        host.tick(&p, out, &mut rng, c);
        // a lone node: its own TX on its RX, so it transmits (and errors: no ACK)
        host.v[p.i("rx")] = out[p.o("tx")];
        host.v.clone()
    };
    let (a, b) = vcds(canstar_controller::core::CanCore::new(), g::can_core::CanCore::from_instance, g::can_core::hdl_set_inputs, &mut stim, g::can_core::hdl_outputs, 20_000);
    same("CanCore", &a, &b);
}

#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn hub_vcd_is_byte_identical() {
    // the network around the hub advances with the hub's outputs of the previous clock
    let mut net = common::hubnet::HubNet::new(common::Ports::of(&g::hub_n3_m2::HubN3M2::new()), 2, 4);
    let mut stim = |c: u64, out: &[u128]| {
        if c > 0 {
            net.advance(out);
        }
        net.inputs(out).to_vec()
    };
    let cfg = canstar_hub::config::HubConfig::default();
    let (a, b) = vcds(canstar_hub::top::Hub::new(&cfg), g::hub_n3_m2::HubN3M2::from_instance, g::hub_n3_m2::hdl_set_inputs, &mut stim, g::hub_n3_m2::hdl_outputs, 10_000);
    same("Hub", &a, &b);
}

#[test]
#[cfg_attr(debug_assertions, ignore = "long: run with cargo test --release")]
fn sja1000_vcd_is_byte_identical() {
    let m0 = g::sja1000::Sja1000::new();
    let mut net = common::sjanet::SjaNet::new(&m0, 1, 5);
    let tx = net.ix.tx;
    let mut stim = |_c: u64, out: &[u128]| {
        net.advance(std::iter::once(out[tx] != 0));
        net.inputs(0, out).to_vec()
    };
    let (a, b) = vcds(canstar_controller::sja1000::Sja1000::new(), g::sja1000::Sja1000::from_instance, g::sja1000::hdl_set_inputs, &mut stim, g::sja1000::hdl_outputs, 10_000);
    same("SJA1000", &a, &b);
}
