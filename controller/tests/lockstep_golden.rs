//! Bit-level lock-step of the RTL frame state machine (`CanFsm`) against the
//! golden behavioural model (canstar-golden) (an independent implementation of
//! can-protocol.md): 2..4 RTL nodes on a wired-AND bus, each with a golden
//! twin fed the same sampled levels; random traffic and random receive-path
//! disturbances (up to error-passive and bus-off). Compared at every bit: the
//! TX level, the bit's label (role, FIELD, POSITION, stuff marker), the §18
//! event tokens, TEC, REC (exact up to 127, then only "> 127", §19) and the
//! delivered frames. The golden request follows the RTL's `tx_rqst` (§19.2).
//!
//! The golden model is the `canstar-golden` crate (it depends on no RTL crate).
#![allow(dead_code, unused_imports, clippy::needless_range_loop, clippy::enum_variant_names)]
use canstar_golden as golden;
mod common;
use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use common::stim::random_frame;
use common::*;
use rand::{Rng, SeedableRng};

fn gframe(f: &Frame) -> golden::Frame {
    golden::Frame { ide: f.ide, id: f.id, rtr: f.rtr, dlc: f.dlc, data: f.data.clone() }
}

fn run(seed: u64, n: usize, rate: f64, bits: usize) {
    run_modes(seed, n, rate, bits, false)
}

fn run_modes(seed: u64, n: usize, rate: f64, bits: usize, modes: bool) {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut b = Bus::new(n);
    // C13: the ISO rule on both sides (the harness's frame state machines default to the
    // 1999 rule of the reference programs; with `modes` each node draws its rule)
    for u in &mut b.nodes {
        u.rec_iso.next = true;
    }
    let mut g: Vec<golden::GoldenNode> = (0..n).map(|_| golden::GoldenNode::default()).collect();
    let mut seen_rqst = vec![false; n];
    if modes {
        for i in 0..n {
            let cfg = golden::Config {
                listen_only: i > 0 && rng.gen_bool(0.3),
                self_test: rng.gen_bool(0.3),
                single_shot: rng.gen_bool(0.4),
                host_recovery: rng.gen_bool(0.5),
                rec_bosch_1999: rng.gen_bool(0.5),
            };
            b.nodes[i].rec_iso.next = !cfg.rec_bosch_1999;
            g[i] = golden::GoldenNode::new(cfg);
            b.nodes[i].listen_only.next = cfg.listen_only;
            b.nodes[i].self_test.next = cfg.self_test;
            b.nodes[i].single_shot.next = cfg.single_shot;
            b.nodes[i].host_recovery.next = cfg.host_recovery;
        }
    }
    let mut glog: Vec<Vec<golden::StepOut>> = vec![vec![]; n];
    let mut want: Vec<Option<Frame>> = vec![None; n];
    let mut gdel: Vec<Vec<golden::Frame>> = vec![vec![]; n];
    for bit in 0..bits {
        for i in 0..n {
            // host-started bus-off recovery, at the same bit in both models
            if b.state(i) == 2 && rng.gen_bool(0.002) {
                b.nodes[i].recover.next = true;
                g[i].start_recovery();
            } else {
                b.nodes[i].recover.next = false;
            }
            if want[i].is_none() && !b.nodes[i].tx_done.val() && bit > 20 && bit < bits - 3000 && rng.gen_bool(0.01) {
                let mut f = random_frame(&mut rng);
                f.id = (f.id & !3) | i as u32;
                b.request(i, &f);
                want[i] = Some(f);
            }
            b.ovr[i] = if bit > 20 && bit < bits - 3000 && rng.gen_bool(rate) {
                [Ovr::StuckD, Ovr::StuckR, Ovr::Invert][rng.gen_range(0..3)]
            } else {
                Ovr::None
            };
        }
        // compare drives before the step
        for i in 0..n {
            let fd = b.nodes[i].drive.val();
            let gd = g[i].drive();
            if fd != gd {
                report(&b, &glog, i, bit, &format!("drive fsm {} golden {}", fd as u8, gd as u8));
            }
        }
        let bus = b.nodes.iter().all(|x| x.drive.val());
        b.step();
        for i in 0..n {
            let smp = b.log[i].last().unwrap().smp;
            let _ = bus;
            let o = g[i].step(smp);
            if let Some(f) = o.delivered() {
                gdel[i].push(f.clone());
            }
            glog[i].push(o);
        }
        for i in 0..n {
            let o = glog[i].last().unwrap();
            // the bit's label (role, FIELD, POSITION, stuff marker); the RTL's
            // POSITION saturates at 255
            let r = b.log[i].last().unwrap();
            let gl = o.label;
            let same = gl.field.name() == r.field.name()
                && (gl.pos as u8 == r.pos || (r.pos == 255 && gl.pos >= 255))
                && gl.stuff == r.stuff
                && (gl.field.is_bare() || (gl.role == golden::Role::Tx) == r.role_tx);
            if !same {
                report(&b, &glog, i, bit, "bit label");
            }
            // the bit's events (state-change and warning tokens are derived
            // from the counters, which are compared below)
            {
                let names = [(EV_SOF,"SOF"),(EV_ARB_LOST,"ARB_LOST"),(EV_BIT_ERR,"BIT_ERR"),(EV_STUFF_ERR,"STUFF_ERR"),(EV_CRC_ERR,"CRC_ERR"),(EV_FORM_ERR,"FORM_ERR"),(EV_ACK_ERR,"ACK_ERR"),(EV_AEF,"AEF"),(EV_PEF,"PEF"),(EV_OLF,"OLF"),(EV_OVL,"OVL"),(EV_DAF,"DAF"),(EV_TX_OK,"TX_OK"),(EV_RX_OK,"RX_OK"),(EV_EXC1,"EXC1"),(EV_EXC2,"EXC2"),(EV_RUN,"RUN"),(EV_RECOVERED,"RECOVERED")];
                let mine: std::collections::BTreeSet<String> = names.iter().filter(|(k,_)| r.has(*k)).map(|(_,n)| n.to_string()).filter(|n| n != "RUN" || !r.has(EV_RECOVERED)).collect();
                let theirs: std::collections::BTreeSet<String> = o.events.iter().map(|e| { let t = e.token(); t.split('=').next().unwrap().to_string() }).filter(|t| !["TO_EP","TO_EA","TO_BO","WARN","WARN_CLR"].contains(&t.as_str())).filter(|t| t != "RUN" || !o.has("RECOVERED")).collect();
                if mine != theirs {
                    report(&b, &glog, i, bit, &format!("events fsm {mine:?} golden {theirs:?}"));
                }
            }
            let (t, r) = (b.tec(i), b.rec(i));
            let rec_ok = if o.rec > 127 { r > 127 } else { r == o.rec as u64 };
            if t != o.tec as u64 || !rec_ok {
                report(&b, &glog, i, bit, &format!("counters fsm {t}/{r} golden {}/{}", o.tec, o.rec));
            }
            if b.rx[i].len() != gdel[i].len() {
                report(&b, &glog, i, bit, &format!("deliveries fsm {} golden {}", b.rx[i].len(), gdel[i].len()));
            }
            // request mirror: the golden request follows the FSM's tx_rqst
            // (once per request: a single-shot golden node clears its request
            // when the attempt starts)
            if b.nodes[i].tx_rqst.val() && !seen_rqst[i] {
                if let Some(f) = &want[i] {
                    g[i].request(gframe(f));
                }
            }
            // end of a request: success, or (single-shot) a failed attempt
            seen_rqst[i] |= b.nodes[i].tx_rqst.val();
            if b.nodes[i].tx_done.val() {
                b.withdraw(i);
                want[i] = None;
                seen_rqst[i] = false;
            } else if seen_rqst[i] && want[i].is_some() && !b.nodes[i].tx_rqst.val() {
                b.withdraw(i);
                g[i].withdraw();
                want[i] = None;
                seen_rqst[i] = false;
            }
        }
    }
    let bo: usize = (0..n).map(|i| b.log[i].iter().filter(|r| r.state == 2).count()).sum();
    let ep: usize = (0..n).map(|i| b.log[i].iter().filter(|r| r.state == 1).count()).sum();
    let _ = (bo, ep);
    eprintln!("seed {seed}: ok, deliveries {:?} passive-bits {ep} busoff-bits {bo}", (0..n).map(|i| b.rx[i].len()).collect::<Vec<_>>());
}

fn report(b: &Bus, glog: &[Vec<golden::StepOut>], i: usize, bit: usize, what: &str) {
    eprintln!("MISMATCH node {i} bit {bit}: {what}");
    let from = bit.saturating_sub(25);
    for j in 0..b.nodes.len() {
        for k in from..=bit.min(b.log[j].len() - 1) {
            let r = &b.log[j][k];
            let o = glog[j].get(k);
            eprintln!(
                "{k:5} N{j} F:{}{:<18} {:>3} {} smp={} drv={} t={} r={} ev={:#x} | G:{:?} {:<18} {:>3} {} drv={} t={} r={} {:?}",
                if r.role_tx { "Tx_" } else { "Rx_" },
                r.field.name(), r.pos, if r.stuff {"S"} else {"-"}, r.smp as u8, r.drv as u8, r.tec, r.rec, r.ev,
                o.map(|o| o.label.role), o.map(|o| o.label.field.name()).unwrap_or(""), o.map(|o| o.label.pos).unwrap_or(0),
                o.map(|o| if o.label.stuff {"S"} else {"-"}).unwrap_or(""), o.map(|o| o.drove as u8).unwrap_or(9),
                o.map(|o| o.tec).unwrap_or(0), o.map(|o| o.rec).unwrap_or(0), o.map(|o| o.events.iter().map(|e| e.token()).collect::<Vec<_>>())
            );
        }
    }
    panic!("lock-step mismatch: node {i} bit {bit}: {what}");
}

#[test]
fn lockstep_modes() {
    for seed in 50..58u64 {
        run_modes(seed, 3, 0.004 * (seed % 3) as f64, 30_000, true);
    }
}

#[test]
fn lockstep_clean() {
    for seed in 0..3 {
        run(seed, 3, 0.0, 30_000);
    }
}

#[test]
fn lockstep_disturbed() {
    for seed in 10..16 {
        run(seed, 3, 0.003 + 0.002 * (seed - 10) as f64, 30_000);
    }
}

#[test]
fn lockstep_heavy() {
    for seed in 20..26u64 {
        let n = 2 + (seed % 3) as usize;
        run(seed, n, 0.005 * (1 + seed % 5) as f64, 40_000);
    }
}

