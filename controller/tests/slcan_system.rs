//! System tests of the slcan top (`SlcanTop`): a Rust host UART model
//! talks slcan to it, and a second SJA1000 (the driver harness of
//! `sja1000_util`, Linux `sja1000` driver sequences) shares the wired-AND
//! CAN bus with it. The host opens the bus, sends standard, extended and
//! remote frames that the node receives, receives the node's frames as
//! lines, gets BEL for each malformed command class, and sees a data
//! overrun in `F`.

mod sja1000_util;
mod slcan_util;

use canstar_controller::frame::Frame;
use canstar_controller::slcan::SlcanParams;
use slcan_util::*;

/// 16 MHz nominal (S6 = 0x00/0x1C: 32 clocks per CAN bit), 8 clocks per
/// UART bit so that the host link is fast in simulation.
fn params(cpb: u32) -> SlcanParams {
    SlcanParams::with_clocks_per_bit(16_000_000, cpb)
}

const BIT: usize = 32;

fn open_both(cpb: u32, rate_cmd: &str) -> (sja1000_util::Net, std::rc::Rc<std::cell::RefCell<SlcanSim>>) {
    let (mut net, sim) = net_with_slcan(1, &params(cpb));
    open_node(&mut net, 0, 0x00, 0x1C);
    let t = 4000 * cpb as usize;
    assert_eq!(command(&mut net, &sim, "C", 1, t), ["\r"]);
    assert_eq!(command(&mut net, &sim, rate_cmd, 1, t), ["\r"]);
    assert_eq!(command(&mut net, &sim, "", 1, t), ["\r"]);
    assert_eq!(command(&mut net, &sim, "O", 1, t), ["\r"]);
    // integration: 11 recessive bits
    net.run(14 * BIT);
    (net, sim)
}

fn host_frames() -> Vec<Frame> {
    vec![
        Frame::data(false, 0x123, 8, &[1, 2, 3, 4, 5, 6, 7, 8]),
        Frame::data(true, 0x1ABCDEF0, 2, &[0xA5, 0x5A]),
        Frame::remote(false, 0x7FF, 3),
        Frame::remote(true, 0x00000001, 0),
        Frame::data(false, 0x000, 0, &[]),
        Frame::data(true, 0x1FFFFFFF, 8, &[0xFF, 0, 0x80, 0x7F, 0x11, 0x22, 0x33, 0x44]),
    ]
}

#[test]
fn frames_both_ways() {
    let (mut net, sim) = open_both(8, "S6");
    // host -> bus: all lines back to back (the adapter waits for the TX
    // buffer between them)
    let frames = host_frames();
    let mut lines = String::new();
    for f in &frames {
        let l = line_of(f);
        lines += &l;
    }
    sim.borrow_mut().send(lines.as_bytes());
    let replies = collect(&mut net, &sim, frames.len(), 200_000);
    let want: Vec<&str> = frames.iter().map(|f| if f.ide { "Z\r" } else { "z\r" }).collect();
    assert_eq!(replies, want);
    net.run_until(200_000, |n| n.drv[0].rx.len() == frames.len());
    assert_eq!(net.drv[0].rx, frames);
    // nothing came back to the host (frames sent with TR are not received back)
    net.run(2000);
    assert_eq!(sim.borrow_mut().take_lines(), Vec::<String>::new());

    // bus -> host
    let mut got = vec![];
    for f in &frames {
        net.xmit(0, f);
        net.run_until(100_000, |n| !n.drv[0].tx_busy);
        got.extend(collect(&mut net, &sim, 1, 100_000));
    }
    let want: Vec<String> = frames.iter().map(line_of).collect();
    assert_eq!(got, want);
    // a received DLC above 8 is sent as 8 with 8 data bytes
    let f = Frame::data(false, 0x42, 12, &[9, 8, 7, 6, 5, 4, 3, 2]);
    net.xmit(0, &f);
    assert_eq!(collect(&mut net, &sim, 1, 100_000), ["t04280908070605040302\r"]);
}

#[test]
fn replies_and_frames_never_interleave() {
    let (mut net, sim) = open_both(8, "S6");
    let frames: Vec<Frame> = (0..6u32).map(|k| Frame::data(k % 2 == 1, 0x100 + k, 8, &[k as u8; 8])).collect();
    let mut queries = 0;
    let mut lines = vec![];
    for f in &frames {
        // the host asks for V, N and F while frames arrive
        sim.borrow_mut().send(b"V\rN\rF\r");
        queries += 3;
        net.xmit(0, f);
        net.run_until(100_000, |n| !n.drv[0].tx_busy);
        lines.extend(sim.borrow_mut().take_lines());
    }
    lines.extend(collect(&mut net, &sim, frames.len() + queries - lines.len(), 200_000));
    let framelines: Vec<String> = lines.iter().filter(|l| l.starts_with('t') || l.starts_with('T')).cloned().collect();
    let want: Vec<String> = frames.iter().map(line_of).collect();
    assert_eq!(framelines, want, "all lines: {lines:?}");
    let others: Vec<&String> = lines.iter().filter(|l| !(l.starts_with('t') || l.starts_with('T'))).collect();
    assert_eq!(others.len(), queries, "{lines:?}");
    for (k, l) in others.iter().enumerate() {
        match k % 3 {
            0 => assert_eq!(l.as_str(), "V0101\r"),
            1 => assert_eq!(l.as_str(), "NCA57\r"),
            _ => assert_eq!(l.as_str(), "F00\r"),
        }
    }
    assert_eq!(sim.borrow().host_ferr, 0);
}

#[test]
fn malformed_commands_answer_bel() {
    let (mut net, sim) = net_with_slcan(1, &params(8));
    open_node(&mut net, 0, 0x00, 0x1C);
    let t = 40_000;
    // closed: no transmission, bad rates
    // (s0010: TSEG1 = 0; s0013: 1 + 4 + 2 = 7 TQ: settings the core refuses)
    for bad in ["t1230", "S", "SA", "S6x", "s01", "s001C0", "s0g1C", "s0010", "s0013", "F1", "X", "Z1"] {
        assert_eq!(command(&mut net, &sim, bad, 1, t), ["\x07"], "{bad:?} (closed)");
    }
    assert_eq!(command(&mut net, &sim, "V", 1, t), ["V0101\r"]);
    assert_eq!(command(&mut net, &sim, "N", 1, t), ["NCA57\r"]);
    assert_eq!(command(&mut net, &sim, "s001C", 1, t), ["\r"]);
    assert_eq!(command(&mut net, &sim, "O", 1, t), ["\r"]);
    net.run(14 * BIT);
    // open: every malformed class, and the commands only valid when closed
    for bad in [
        "t12",               // too short
        "t1239",             // DLC > 8
        "t12g1AA",           // bad hex
        "t8001AA",           // standard identifier > 0x7FF
        "T200000000",        // extended identifier > 0x1FFFFFFF
        "t123201",           // wrong length (odd)
        "t12320102AA",       // wrong length (long)
        "r12389",            // remote frame with data
        "R1234567",          // short extended identifier
        "T1234567890102030405060708", // DLC 9
        "t1238000102030405060708090A0B0C0D0E0F10", // far too long
        "S6",                // only when closed
        "s001C",
        "O",                 // already open
        "L",
        "Ox",
        "Cx",
        "q",
    ] {
        assert_eq!(command(&mut net, &sim, bad, 1, t), ["\x07"], "{bad:?} (open)");
    }
    // nothing reached the bus
    net.run(300 * BIT);
    assert!(net.drv[0].rx.is_empty(), "{:?}", net.drv[0].rx);
    // a good line still works after all that
    assert_eq!(command(&mut net, &sim, "t7FF0", 1, t), ["z\r"]);
    net.run_until(100_000, |n| n.drv[0].rx.len() == 1);
    assert_eq!(net.drv[0].rx, [Frame::data(false, 0x7FF, 0, &[])]);
    // listen-only: transmission refused, reception works
    assert_eq!(command(&mut net, &sim, "C", 1, t), ["\r"]);
    assert_eq!(command(&mut net, &sim, "L", 1, t), ["\r"]);
    net.run(14 * BIT);
    assert_eq!(command(&mut net, &sim, "t1230", 1, t), ["\x07"]);
    // (a second node acknowledges: listen-only sends no ACK)
    net.drv[0].mode.presume_ack = true;
    net.set_reset_mode(0);
    net.start(0);
    net.run(14 * BIT);
    let f = Frame::data(true, 0x15555555, 1, &[0x3C]);
    net.xmit(0, &f);
    assert_eq!(collect(&mut net, &sim, 1, 100_000), [line_of(&f)]);
}

#[test]
fn overrun_shows_in_f() {
    // a slow host link (64 clocks per UART bit: a frame line takes 14 000
    // clocks, the frame on the bus 4 000): the SJA1000's FIFO overflows
    let (mut net, sim) = open_both(64, "s001C");
    let frames: Vec<Frame> = (0..12u32).map(|k| Frame::data(false, k, 8, &[k as u8; 8])).collect();
    for f in &frames {
        net.xmit(0, f);
        net.run_until(100_000, |n| !n.drv[0].tx_busy);
    }
    // drain what was kept
    let mut lines = vec![];
    loop {
        let before = lines.len();
        net.run(40_000);
        lines.extend(sim.borrow_mut().take_lines());
        if lines.len() == before {
            break;
        }
    }
    assert!(lines.len() < frames.len(), "no frame lost: {lines:?}");
    assert!(lines.len() >= 5, "{lines:?}");
    // the lines kept are whole frames in bus order: the first ones (the
    // FIFO filling up), then those that found room again
    let want: Vec<String> = frames.iter().map(line_of).collect();
    assert_eq!(lines[..5], want[..5]);
    let mut at = 0;
    for l in &lines {
        at += want[at..].iter().position(|w| w == l).unwrap_or_else(|| panic!("{l:?} not a sent frame in order: {lines:?}")) + 1;
    }
    // F: RX FIFO full (bit 0) and data overrun (bit 3); reading clears them
    assert_eq!(command(&mut net, &sim, "F", 1, 100_000), ["F09\r"]);
    assert_eq!(command(&mut net, &sim, "F", 1, 100_000), ["F00\r"]);
    // reception goes on
    net.xmit(0, &frames[0]);
    assert_eq!(collect(&mut net, &sim, 1, 100_000), [want[0].clone()]);
}

#[test]
fn bus_off_refuses_transmission() {
    let (mut net, sim) = open_both(8, "S6");
    // the adapter's receiver stuck recessive: every dominant bit it sends is
    // a bit error, TEC += 8 per attempt, bus-off after 32
    sim.borrow_mut().rx_force = Some(true);
    assert_eq!(command(&mut net, &sim, "t1230", 1, 40_000), ["z\r"]);
    net.run(60 * 32 * BIT);
    // bus-off: the block is in reset mode; a frame line must not be loaded
    // into 0x10.. (the acceptance registers there)
    assert_eq!(command(&mut net, &sim, "t1241AA", 1, 40_000), ["\x07"]);
    sim.borrow_mut().rx_force = None;
    // close and reopen: the recovery (128 x 11 recessive bits), then frames
    // flow both ways with the filter intact
    assert_eq!(command(&mut net, &sim, "C", 1, 40_000), ["\r"]);
    assert_eq!(command(&mut net, &sim, "O", 1, 40_000), ["\r"]);
    net.run(130 * 11 * BIT);
    let f = Frame::data(true, 0x0BADCAFE, 2, &[1, 2]);
    net.xmit(0, &f);
    assert_eq!(collect(&mut net, &sim, 1, 100_000), [line_of(&f)]);
    assert_eq!(command(&mut net, &sim, "t1241AA", 1, 40_000), ["z\r"]);
    net.run_until(100_000, |n| n.drv[0].rx.len() == 1);
    assert_eq!(net.drv[0].rx, [Frame::data(false, 0x124, 1, &[0xAA])]);
}
