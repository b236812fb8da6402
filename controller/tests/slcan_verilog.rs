//! The Verilog flow of the slcan top (`SlcanTop`: UART, queue, parser,
//! line transmitter, engine and the SJA1000): Verilator lint, Yosys
//! synthesis (generic: latch-free; iCE40: the LC count) and co-simulation
//! of the emitted Verilog against the Rust model on a host-like stimulus:
//! a host UART that opens the channel (C, S6 or s001C, empty line, O) and
//! then sends a random mix of valid frame lines, malformed lines, F, V, N,
//! garbage bytes, characters with a bad stop bit and start-bit glitches,
//! sometimes closes and reopens; a peer `CanCore` on the wired-AND bus
//! (S6 timing) that sends random frames and acknowledges; a hardware
//! reset now and then.

use canstar_controller::core::CanCore;
use canstar_controller::frame::Frame;
use canstar_controller::sja1000::timing::core_timing;
use canstar_controller::slcan::{SlcanParams, SlcanTop};
use canstar_hdl::{drive, flow};
use rand::Rng;
use std::cell::RefCell;
use std::collections::VecDeque;
use std::rc::Rc;

const CPB: u32 = 4;
const CYCLES: usize = 120_000;

#[derive(Default, Clone, Debug)]
struct Seen {
    lines: usize,
    z: usize,
    bel: usize,
    frames_to_host: usize,
    f_replies: usize,
    peer_rx: usize,
    peer_tx: usize,
    resets: usize,
}

fn params() -> SlcanParams {
    SlcanParams::with_clocks_per_bit(16_000_000, CPB)
}

fn random_line<R: Rng>(rng: &mut R) -> Vec<u8> {
    let ide = rng.gen_bool(0.4);
    let rtr = rng.gen_bool(0.2);
    let dlc = rng.gen_range(0..=8u8);
    let id = if ide { rng.gen_range(0..1u32 << 29) } else { rng.gen_range(0..2048) };
    let mut s = match (ide, rtr) {
        (false, false) => format!("t{id:03X}{dlc}"),
        (true, false) => format!("T{id:08X}{dlc}"),
        (false, true) => format!("r{id:03X}{dlc}"),
        (true, true) => format!("R{id:08X}{dlc}"),
    };
    if !rtr {
        for _ in 0..dlc {
            s += &format!("{:02x}", rng.gen::<u8>());
        }
    }
    match rng.gen_range(0..20) {
        0 => s = "F".into(),
        1 => s = "V".into(),
        2 => s = "N".into(),
        3 => s = String::new(),
        4 => s.push('g'),                    // malformed
        5 => s = format!("t9{}", &s[2..]),   // std id too large or short
        6 => s = "C".into(),
        7 => s = "O".into(),
        8 => s = ["S6", "S8", "s001C", "S9"][rng.gen_range(0..4)].into(),
        9 => s = (0..rng.gen_range(1..40)).map(|_| rng.gen_range(0x20u8..0x7F) as char).collect(),
        _ => {}
    }
    let mut v = s.into_bytes();
    v.push(b'\r');
    v
}

fn stimulus(st: Rc<RefCell<Seen>>) -> impl FnMut(&mut SlcanTop, &mut rand_chacha::ChaCha8Rng, usize) {
    let mut peer = Box::new(CanCore::new());
    drive::init(&mut *peer);
    peer.set_timing(&core_timing(0x00, 0x1C).unwrap());
    peer.reset.next = true;
    let cpb = CPB as usize;
    let mut host: VecDeque<u8> = VecDeque::new();
    let mut levels: VecDeque<bool> = VecDeque::new();
    let mut rx_at: Option<usize> = None;
    let mut rx_bits = 0u16;
    let mut last = true;
    let mut got: Vec<u8> = vec![];
    let mut opened = false;
    move |u, rng, cycle| {
        let mut s = st.borrow_mut();
        // ---- the host receiver (mid-bit samples of uart_tx)
        let l = u.uart_tx.val();
        match rx_at {
            None if last && !l => {
                rx_at = Some(0);
                rx_bits = 0;
            }
            None => {}
            Some(t) => {
                let t = t + 1;
                rx_at = Some(t);
                if t >= cpb / 2 && (t - cpb / 2) % cpb == 0 {
                    let k = (t - cpb / 2) / cpb;
                    if (1..=8).contains(&k) {
                        rx_bits |= (l as u16) << (k - 1);
                    } else if k == 9 {
                        rx_at = None;
                        let b = rx_bits as u8;
                        got.push(b);
                        if b == b'\r' || b == 7 {
                            s.lines += 1;
                            match got.first() {
                                Some(7) => s.bel += 1,
                                Some(b'z') | Some(b'Z') => s.z += 1,
                                Some(b'F') => s.f_replies += 1,
                                Some(b't') | Some(b'T') | Some(b'r') | Some(b'R') => s.frames_to_host += 1,
                                _ => {}
                            }
                            got.clear();
                        }
                    }
                }
            }
        }
        last = l;
        // ---- the host transmitter
        if !opened && host.is_empty() {
            host.extend(b"C\rS6\r\rO\r");
            opened = true;
        }
        if levels.is_empty() {
            if host.is_empty() && rng.gen_bool(0.01) {
                host.extend(random_line(rng));
            }
            if let Some(b) = host.pop_front() {
                let stop = !rng.gen_bool(0.003); // a framing error now and then
                levels.extend(std::iter::repeat(false).take(cpb));
                for k in 0..8 {
                    levels.extend(std::iter::repeat(b >> k & 1 == 1).take(cpb));
                }
                levels.extend(std::iter::repeat(stop).take(cpb));
            } else if rng.gen_bool(0.001) {
                levels.push_back(false); // a start-bit glitch
            }
        }
        u.uart_rx.next = levels.pop_front().unwrap_or(true);
        // ---- the bus
        let bus = u.tx.val() && peer.tx.val();
        u.rx.next = bus;
        peer.rx.next = bus;
        peer.reset.next = cycle < 4;
        if peer.tx_done.val() || peer.arb_lost.val() {
            peer.tx_req.next = false;
            s.peer_tx += peer.tx_done.val() as usize;
        }
        if peer.tec.val().index() >= 96 {
            peer.tx_req.next = false;
        }
        s.peer_rx += peer.rx_valid.val() as usize;
        if !peer.tx_req.val() && rng.gen_bool(0.0002) {
            let ide = rng.gen_bool(0.4);
            let id = if ide { rng.gen_range(0..1u32 << 29) } else { rng.gen_range(0..2048) };
            let f = if rng.gen_bool(0.2) {
                Frame::remote(ide, id, rng.gen_range(0..16))
            } else {
                let d: Vec<u8> = (0..8).map(|_| rng.gen()).collect();
                Frame::data(ide, id, rng.gen_range(0..16), &d)
            };
            peer.tx_ide.next = f.ide;
            peer.tx_rtr.next = f.rtr;
            peer.tx_id.next = (f.id as u64).into();
            peer.tx_dlc.next = (f.dlc as u64).into();
            peer.tx_data.next = f.data_word().into();
            peer.tx_req.next = true;
        }
        drive::cycle(&mut *peer);
        // ---- hardware reset: at the start and twice later
        u.rst.next = cycle < 3 || cycle == 70_000 || cycle == 100_000;
        if cycle == 70_000 || cycle == 100_000 {
            s.resets += 1;
            host.clear();
            levels.clear();
            rx_at = None;
            got.clear();
            opened = false;
        }
    }
}

fn check_coverage(s: &Seen) {
    assert!(s.lines > 50, "{s:?}");
    assert!(s.z >= 5, "{s:?}");
    assert!(s.bel >= 5, "{s:?}");
    assert!(s.frames_to_host >= 3, "{s:?}");
    assert!(s.f_replies >= 1, "{s:?}");
    assert!(s.peer_rx >= 5 && s.peer_tx >= 3, "{s:?}");
}

/// The stimulus on the Rust model only (no tools needed): it reaches
/// transmissions both ways, BEL replies and F.
#[test]
fn slcan_stimulus_coverage() {
    let seen = Rc::new(RefCell::new(Seen::default()));
    let mut stim = stimulus(seen.clone());
    let mut u = SlcanTop::new(&params());
    drive::init(&mut u);
    let mut rng = flow::rng(18);
    let t0 = std::time::Instant::now();
    for cycle in 0..CYCLES {
        stim(&mut u, &mut rng, cycle);
        drive::cycle(&mut u);
    }
    let s = seen.borrow().clone();
    eprintln!("seen {s:?}; {:.0} clocks/s (SlcanTop + a CanCore peer, rust-hdl)", CYCLES as f64 / t0.elapsed().as_secs_f64());
    check_coverage(&s);
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn slcan_verilog_flow() {
    let mut u = SlcanTop::new(&params());
    drive::init(&mut u);
    let verilog = flow::emit(&u);
    let ice = flow::synth_check(&verilog, "top", flow::SynthTarget::Ice40).expect("iCE40 synthesis");
    let lc = ice.stat.lines().find(|l| l.contains("SB_LUT4")).unwrap_or("").trim().to_string();
    eprintln!("iCE40: {} cells, {lc}\n{}", ice.cells, ice.stat);
    let seen = Rc::new(RefCell::new(Seen::default()));
    let (synth, cs) = flow::full_check(&mut u, "slcan", CYCLES, 18, stimulus(seen.clone())).expect("slcan Verilog flow");
    let s = seen.borrow().clone();
    eprintln!("generic synth cells: {}; cosim {} cycles; seen {:?}", synth.cells, cs.cycles, s);
    assert!(cs.cycles >= 100_000);
    check_coverage(&s);
}
