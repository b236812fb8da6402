//! The Verilog flow of the SJA1000 register block: Verilator lint, Yosys
//! synthesis (generic: latch-free; iCE40: cell and block RAM counts) and a
//! co-simulation of the emitted Verilog against the Rust model over a
//! driver-like stimulus: a Wishbone master that initialises the block like
//! the Linux driver, transmits (TR, SRR, single shot, aborts), services
//! interrupts (IR, SR, ALC, ECC, RX window, RRB, CDO), changes modes,
//! filters, bit timing and counters in reset mode, sleeps; a peer CanCore on
//! the same wired-AND bus that transmits, sometimes at the same moment
//! (arbitration), sometimes is held in reset (no ACK); bus disturbances and
//! long dominant jams (bus-off), and a hardware reset now and then.
use canstar_controller::core::CanCore;
use canstar_controller::frame::Frame;
use canstar_controller::sja1000::*;
use canstar_hdl::{drive, flow};
use rand::Rng;
use std::cell::RefCell;
use std::collections::VecDeque;
use std::rc::Rc;

#[derive(Default, Clone, Debug)]
struct Seen {
    ir: u8,
    sr: u8,
    max_rmc: u8,
    modes: u8,
    reads: usize,
    writes: usize,
    peer_rx: usize,
    peer_tx: usize,
    /// reads of TXERR/RXERR that returned a host-written value (255, 140, 130)
    loaded: usize,
}

fn random_frame<R: Rng>(rng: &mut R) -> Frame {
    let ide = rng.gen_bool(0.4);
    let id = if ide { rng.gen_range(0..1u32 << 29) } else { rng.gen_range(0..2048) };
    let dlc = rng.gen_range(0..16u8);
    if rng.gen_bool(0.15) {
        Frame::remote(ide, id, dlc)
    } else {
        let d: Vec<u8> = (0..8).map(|_| rng.gen()).collect();
        Frame::data(ide, id, dlc, &d)
    }
}

fn push_tx<R: Rng>(q: &mut VecDeque<(bool, u8, u8)>, rng: &mut R, f: &Frame) {
    let mut fi = f.dlc;
    if f.rtr {
        fi |= FI_RTR;
    }
    if f.ide {
        fi |= FI_FF;
        q.push_back((true, 0x10, fi));
        q.push_back((true, 0x11, (f.id >> 21) as u8));
        q.push_back((true, 0x12, (f.id >> 13) as u8));
        q.push_back((true, 0x13, (f.id >> 5) as u8));
        q.push_back((true, 0x14, (f.id << 3) as u8));
        for (k, b) in f.data.iter().enumerate() {
            q.push_back((true, 0x15 + k as u8, *b));
        }
    } else {
        q.push_back((true, 0x10, fi));
        q.push_back((true, 0x11, (f.id >> 3) as u8));
        q.push_back((true, 0x12, (f.id << 5) as u8));
        for (k, b) in f.data.iter().enumerate() {
            q.push_back((true, 0x13 + k as u8, *b));
        }
    }
    let cmd = [CMD_TR, CMD_TR, CMD_TR, CMD_SRR, CMD_TR | CMD_AT, CMD_SRR | CMD_AT][rng.gen_range(0..6)];
    q.push_back((true, REG_CMR, cmd));
}

fn push_init<R: Rng>(q: &mut VecDeque<(bool, u8, u8)>, rng: &mut R, odd_timing: bool, first: bool) {
    q.push_back((true, REG_IER, 0));
    q.push_back((true, REG_MOD, MOD_RM));
    q.push_back((false, REG_MOD, 0));
    q.push_back((true, REG_CDR, 0xC8));
    let (b0, b1) = if odd_timing { [(0x00u8, 0x1Cu8), (0x01, 0x25), (0x80, 0x14), (0x3F, 0x7F)][rng.gen_range(0..4)] } else { (0x40, 0x25) };
    q.push_back((true, REG_BTR0, b0));
    q.push_back((true, REG_BTR1, b1 | if rng.gen_bool(0.2) { 0x80 } else { 0 }));
    if rng.gen_bool(0.5) || first {
        for k in 0..4 {
            q.push_back((true, REG_ACCC0 + k, 0));
            q.push_back((true, REG_ACCM0 + k, 0xFF));
        }
    } else {
        for k in 0..8 {
            let v = if k >= 4 && rng.gen_bool(0.6) { 0xFF } else { rng.gen() };
            q.push_back((true, REG_ACCC0 + k, v));
        }
    }
    q.push_back((true, REG_EWL, [96u8, 96, 1, 200][rng.gen_range(0..4)]));
    // counters: the core continues from them (255: a CPU-driven bus-off);
    // the deterministic phases start from 0
    let (tec, rec) = if first { (0, 0) } else { ([0u8, 0, 100, 140, 255][rng.gen_range(0..5)], [0u8, 0, 130][rng.gen_range(0..3)]) };
    q.push_back((true, REG_TXERR, tec));
    q.push_back((true, REG_RXERR, rec));
    if rng.gen_bool(0.3) {
        q.push_back((false, REG_TXERR, 0));
        q.push_back((false, REG_RXERR, 0));
    }
    if rng.gen_bool(0.2) {
        q.push_back((true, REG_RBSA, rng.gen()));
    }
    if rng.gen_bool(0.2) {
        let a: u8 = rng.gen_range(0x20..0x60);
        q.push_back((true, a, rng.gen()));
        q.push_back((false, a, 0));
    }
    q.push_back((false, REG_ECC, 0));
    q.push_back((false, REG_IR, 0));
    let mut m = 0;
    if rng.gen_bool(0.1) && !first {
        m |= MOD_LOM;
    }
    if rng.gen_bool(0.15) && !first {
        m |= MOD_STM;
    }
    if rng.gen_bool(0.5) {
        m |= MOD_AFM;
    }
    q.push_back((true, REG_MOD, m));
    q.push_back((true, REG_IER, if rng.gen_bool(0.8) || first { 0xFF } else { rng.gen() }));
}

/// The driver-like stimulus (see the module documentation); `seen`
/// collects what the host read back.
fn stimulus(st: Rc<RefCell<Seen>>) -> impl FnMut(&mut Sja1000, &mut rand_chacha::ChaCha8Rng, usize) {
    let mut peer = Box::new(CanCore::new());
    drive::init(&mut *peer);
    // BTR0 0x40 / BTR1 0x25 as the block maps it: BRP 2 clocks, PROP 1, PH1 5, PH2 3, SJW 2
    peer.brp.next = 1u64.into();
    peer.prop.next = 0u64.into();
    peer.ph1.next = 4u64.into();
    peer.ph2.next = 2u64.into();
    peer.sjw.next = 1u64.into();
    peer.reset.next = true;
    let mut q: VecDeque<(bool, u8, u8)> = VecDeque::new();
    let mut stage = 0u32;
    let mut cur = (false, 0u8, 0u8);
    let mut jam = 0u32;
    let mut peer_off = 0u32;
    let mut deaf = 0u32;
    let mut idle_gap = 0u32;
    let mut last_sr = 0u8;
    move |u, rng, cycle| {
        let mut s = st.borrow_mut();
        // ---- the bus: block, peer and disturbances
        if jam == 0 && rng.gen_bool(0.00004) {
            jam = rng.gen_range(1..40); // a short disturbance
        }
        if jam == 0 && rng.gen_bool(0.000006) {
            jam = rng.gen_range(4_000..12_000); // long dominant jam: bus-off
        }
        let bus = u.tx.val() && peer.tx.val() && jam == 0;
        jam = jam.saturating_sub(1);
        u.rx.next = bus;
        peer.rx.next = bus;
        if peer.state.val().index() == 2 && peer_off == 0 {
            peer_off = 50; // the peer's host restarts it after bus-off
        }
        if peer.tec.val().index() >= 128 && peer.tx_req.val() {
            peer.tx_req.next = false; // and gives up when error passive
        }
        if peer_off == 0 && rng.gen_bool(0.00002) && !(15_000..50_000).contains(&cycle) {
            peer_off = rng.gen_range(5_000..30_000);
        }
        peer.reset.next = cycle < 4 || peer_off > 0;
        peer_off = peer_off.saturating_sub(1);
        if peer.tx_done.val() || peer.arb_lost.val() && rng.gen_bool(0.3) {
            peer.tx_req.next = false;
            s.peer_tx += peer.tx_done.val() as usize;
        }
        s.peer_rx += peer.rx_valid.val() as usize;
        // deterministic phases: 20k..45k the host is deaf while the peer
        // sends back to back (FIFO full, overrun); 55k..75k the block's
        // receiver is stuck recessive while it transmits (bus-off);
        // 85k the host puts the block to sleep, the peer wakes it
        let deaf_phase = (20_000..45_000).contains(&cycle);
        let stuck_phase = (55_000..75_000).contains(&cycle);
        if stuck_phase {
            u.rx.next = true;
        }
        if !peer.tx_req.val() && (rng.gen_bool(0.0004) || (deaf_phase && rng.gen_bool(0.01))) {
            let mut f = random_frame(rng);
            if deaf_phase {
                f = Frame::data(f.ide, f.id, 8, &[0x5A; 8]);
            }
            peer.tx_ide.next = f.ide;
            peer.tx_rtr.next = f.rtr;
            peer.tx_id.next = (f.id as u64).into();
            peer.tx_dlc.next = (f.dlc as u64).into();
            peer.tx_data.next = f.data_word().into();
            peer.tx_req.next = true;
        }
        drive::cycle(&mut *peer);
        if std::env::var("SJA_DBG").is_ok() && peer.error.val() && (20_000..45_000).contains(&cycle) {
            eprintln!("{cycle}: peer error kind {:b} field {} pos {} tx {}", peer.err_kind.val().index(), peer.err_field.val().index(), peer.err_pos.val().index(), peer.err_tx.val());
        }
        if std::env::var("SJA_DBG").is_ok() && cycle % 5000 == 0 {
            eprintln!("{cycle}: peer field {} tec {} rec {} req {} off {peer_off} jam {jam} bus {bus} utx {}", peer.dbg_field.val().index(), peer.tec.val().index(), peer.rec.val().index(), peer.tx_req.val(), u.tx.val());
        }

        // ---- hardware reset
        let rst = cycle < 3 || cycle == 100_000;
        u.rst.next = rst;
        if cycle < 3 || cycle == 100_000 {
            q.clear();
            stage = 0;
            push_init(&mut q, rng, false, true);
        }

        // ---- Wishbone master
        match stage {
            0 => {
                if idle_gap > 0 {
                    idle_gap -= 1;
                } else if let Some(op) = q.pop_front() {
                    cur = op;
                    stage = 1;
                    if rng.gen_bool(0.1) {
                        idle_gap = rng.gen_range(0..20);
                    }
                }
            }
            1 => stage = 2,
            _ => {
                // ack cycle just completed: look at read data
                if !cur.0 {
                    let d = u.wb_dat_r.val().index() as u8;
                    if std::env::var("SJA_DBG").is_ok() && (85_000..95_000).contains(&cycle) {
                        eprintln!("{cycle}: read {:#x} = {d:#x}", cur.1);
                    }
                    s.reads += 1;
                    match cur.1 {
                        REG_IR => s.ir |= d,
                        REG_SR => {
                            s.sr |= d;
                            last_sr = d;
                        }
                        REG_RMC => s.max_rmc = s.max_rmc.max(d),
                        REG_MOD => s.modes |= d,
                        REG_TXERR if d == 255 || d == 140 => s.loaded += 1,
                        REG_RXERR if d == 130 => s.loaded += 1,
                        _ => {}
                    }
                } else {
                    s.writes += 1;
                }
                stage = 0;
            }
        }
        let active = stage == 1 || stage == 2;
        u.wb_cyc.next = active;
        u.wb_stb.next = active;
        u.wb_we.next = cur.0;
        u.wb_adr.next = (cur.1 as u64 | if rng.gen_bool(0.05) { 0x80 } else { 0 }).into();
        u.wb_dat_w.next = (cur.2 as u64).into();
        if stage == 2 && !active {
            unreachable!();
        }

        // ---- the host program
        if cycle == 19_000 || cycle == 54_000 {
            push_init(&mut q, rng, false, true);
        }
        if cycle == 55_000 {
            let f = random_frame(rng);
            push_tx(&mut q, rng, &f);
        }
        if cycle == 76_000 {
            push_init(&mut q, rng, false, true);
        }
        if (85_000..95_000).contains(&cycle) && cycle % 1000 == 0 {
            // go to sleep (refused while an interrupt is pending or the bus is busy)
            q.push_back((true, REG_IER, 0xFF));
            q.push_back((false, REG_IR, 0));
            for _ in 0..8 {
                q.push_back((true, REG_CMR, CMD_RRB));
            }
            q.push_back((false, REG_IR, 0));
            q.push_back((true, REG_MOD, MOD_SM));
            q.push_back((false, REG_MOD, 0));
            q.push_back((false, REG_IER, 0));
            q.push_back((false, REG_SR, 0));
        }
        if q.is_empty() && stage == 0 {
            deaf = deaf.saturating_sub(1);
            if !u.int_n.val() && deaf == 0 && !deaf_phase {
                // interrupt service like the Linux driver
                q.push_back((false, REG_IR, 0));
                q.push_back((false, REG_SR, 0));
                q.push_back((false, REG_RMC, 0));
                q.push_back((false, REG_ALC, 0));
                q.push_back((false, REG_ECC, 0));
                q.push_back((false, REG_TXERR, 0));
                q.push_back((false, REG_RXERR, 0));
                for k in 0..rng.gen_range(1..13u8) {
                    q.push_back((false, REG_FI + k, 0));
                }
                q.push_back((true, REG_CMR, CMD_RRB | if rng.gen_bool(0.3) { CMD_CDO } else { 0 }));
                if last_sr & SR_BS != 0 && !stuck_phase {
                    // bus-off restart like the driver: reset mode, counters, normal mode
                    push_init(&mut q, rng, false, false);
                    last_sr = 0;
                }
            } else {
                let r: f64 = rng.gen();
                if r < 0.001 && !(80_000..95_000).contains(&cycle) {
                    let f = random_frame(rng);
                    push_tx(&mut q, rng, &f);
                    if rng.gen_bool(0.4) && !peer.tx_req.val() {
                        // the peer wants the bus at the same time: arbitration
                        let g = Frame { id: f.id ^ (1 << rng.gen_range(0..if f.ide { 29 } else { 11 })), ..f.clone() };
                        peer.tx_ide.next = g.ide;
                        peer.tx_rtr.next = g.rtr;
                        peer.tx_id.next = (g.id as u64).into();
                        peer.tx_dlc.next = (g.dlc as u64).into();
                        peer.tx_data.next = g.data_word().into();
                        peer.tx_req.next = true;
                    }
                    if rng.gen_bool(0.1) {
                        q.push_back((true, REG_CMR, CMD_AT));
                    }
                } else if deaf_phase {
                    // the host is busy elsewhere
                } else if (50_000..95_000).contains(&cycle) {
                    // only the phases above here
                } else if r < 0.0015 {
                    q.push_back((false, rng.gen_range(0..128), 0));
                } else if r < 0.0016 {
                    q.push_back((true, rng.gen_range(0..128), rng.gen()));
                } else if r < 0.00165 {
                    let odd = rng.gen_bool(0.15);
                    push_init(&mut q, rng, odd, false);
                } else if r < 0.00168 {
                    q.push_back((true, REG_MOD, if rng.gen_bool(0.7) { MOD_SM } else { 0 }));
                } else if r < 0.002 {
                    q.push_back((false, REG_SR, 0));
                    q.push_back((false, REG_MOD, 0));
                }
            }
        }
        let _ = cycle;
    }
}

const CYCLES: usize = 120_000;

fn check_coverage(s: &Seen) {
    // the stimulus reached the interesting states
    for (bit, name) in [
        (IRQ_RI, "RI"),
        (IRQ_TI, "TI"),
        (IRQ_EI, "EI"),
        (IRQ_DOI, "DOI"),
        (IRQ_EPI, "EPI"),
        (IRQ_WUI, "WUI"),
        (IRQ_ALI, "ALI"),
        (IRQ_BEI, "BEI"),
    ] {
        assert!(s.ir & bit != 0, "interrupt {name} never seen: {s:?}");
    }
    assert!(s.sr & SR_BS != 0, "bus-off never seen");
    assert!(s.sr & SR_DOS != 0, "data overrun never seen");
    assert!(s.max_rmc >= 3);
    assert!(s.loaded >= 1, "no counter write read back");
    assert!(s.peer_rx > 10 && s.peer_tx > 10);
}

/// The same stimulus on the Rust model only (no tools needed): it reaches
/// every interrupt source, overrun and bus-off.
#[test]
fn sja1000_driver_stimulus_coverage() {
    let seen = Rc::new(RefCell::new(Seen::default()));
    let mut stim = stimulus(seen.clone());
    let mut u = Sja1000::new();
    drive::init(&mut u);
    let mut rng = flow::rng(11);
    for cycle in 0..CYCLES {
        stim(&mut u, &mut rng, cycle);
        drive::cycle(&mut u);
    }
    let s = seen.borrow().clone();
    eprintln!("seen {s:?}");
    check_coverage(&s);
}

#[test]
#[ignore = "needs iverilog, verilator and yosys: run scripts/test-all.sh"]
fn sja1000_verilog_flow() {
    let mut u = Sja1000::new();
    drive::init(&mut u);
    let verilog = flow::emit(&u);
    let ice = flow::synth_check(&verilog, "top", flow::SynthTarget::Ice40).expect("iCE40 synthesis");
    eprintln!("iCE40:\n{}", ice.stat);
    assert!(ice.stat.contains("SB_RAM40_4K"), "the RX FIFO maps to block RAM");
    let seen = Rc::new(RefCell::new(Seen::default()));
    let (synth, cs) = flow::full_check(&mut u, "sja1000", CYCLES, 11, stimulus(seen.clone())).expect("SJA1000 Verilog flow");
    let s = seen.borrow().clone();
    eprintln!("generic synth cells: {}; cosim {} cycles; seen {:?}", synth.cells, cs.cycles, s);
    assert!(cs.cycles >= 100_000);
    check_coverage(&s);
}
