//! Randomised checks of derived nets against brute-force references, and of
//! the event enumeration the VCD writer relies on.

use canstar_sim::{NetId, Sim};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_drive(sim: &mut Sim, rng: &mut ChaCha8Rng, nets: &[NetId], until: u64) {
    let mut t = 0;
    while t < until {
        t += rng.gen_range(1..40);
        sim.run_until(t);
        let k = rng.gen_range(0..nets.len());
        sim.drive(nets[k], rng.gen_bool(0.6));
    }
}

#[test]
fn asymmetric_delay_matches_window_reference() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..40 {
        let mut sim = Sim::new(0);
        let src = sim.driven("src", true);
        let dd = rng.gen_range(0..50u64);
        let dr = rng.gen_range(0..50u64);
        let d = sim.delay("d", src, dd, dr);
        random_drive(&mut sim, &mut rng, &[src], 3000);
        sim.run_until(3200);
        let (lo, hi) = (dd.max(dr), dd.min(dr));
        for t in lo..3200 {
            let window = (t - lo..=t - hi).map(|u| sim.value_at(src, u));
            let expect = if dr >= dd { window.clone().all(|v| v) } else { window.clone().any(|v| v) };
            assert_eq!(sim.value_at(d, t), expect, "dD={dd} dR={dr} t={t}");
        }
    }
}

/// Waveform of wire `path` in a VCD file: (time, level) for each change.
fn vcd_wave(file: &std::path::Path, path: &[&str]) -> Vec<(u64, bool)> {
    let mut p = vcd::Parser::new(std::io::BufReader::new(std::fs::File::open(file).unwrap()));
    let header = p.parse_header().unwrap();
    let id = header.find_var(path).unwrap_or_else(|| panic!("no var {path:?}")).code;
    let mut t = 0;
    let mut out = Vec::new();
    for cmd in p {
        match cmd.unwrap() {
            vcd::Command::Timestamp(x) => t = x,
            vcd::Command::ChangeScalar(i, v) if i == id => out.push((t, v == vcd::Value::V1)),
            _ => {}
        }
    }
    out
}

#[test]
fn vcd_wires_show_every_change_of_nested_nets_at_its_exact_time() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let dir = tempfile::tempdir().unwrap();
    for round in 0..20 {
        let mut sim = Sim::new(0);
        let a = sim.driven("a", true);
        let b = sim.driven("b", true);
        let da = sim.delay("da", a, rng.gen_range(0..30), rng.gen_range(0..30));
        let db = sim.delay("db", b, rng.gen_range(0..30), rng.gen_range(0..30));
        let w = sim.wired_and("w", &[da, db]);
        let dw = sim.delay("x.dw", w, rng.gen_range(0..30), rng.gen_range(0..30));
        let f = sim.fault("x.f", dw);
        sim.schedule_fault(f, 500, canstar_sim::FaultMode::Invert);
        sim.schedule_fault(f, 900, canstar_sim::FaultMode::None);
        sim.add_flip_window(f, 1200, 1213);
        let file = dir.path().join(format!("r{round}.vcd"));
        sim.start_vcd_file(&file, None).unwrap();
        random_drive(&mut sim, &mut rng, &[a, b], 2000);
        sim.run_until(2100);
        sim.finish_vcd().unwrap();
        for (net, path) in [(f, vec!["sim", "x", "f"]), (w, vec!["sim", "w"]), (da, vec!["sim", "da"])] {
            let mut expect = vec![(0, sim.value_at(net, 0))];
            expect.extend(
                (1..2100).filter(|&t| sim.value_at(net, t) != sim.value_at(net, t - 1)).map(|t| (t, sim.value_at(net, t))),
            );
            assert_eq!(vcd_wave(&file, &path), expect, "round {round} {path:?}");
        }
    }
}
