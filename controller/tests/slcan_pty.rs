//! python-can's `slcan` interface, unchanged, against the simulated slcan
//! top: a pseudo-terminal pair in raw mode, `python3 slcan_pty_client.py
//! <slave path>` on one side, and on the other the `SlcanTop` (16 MHz
//! nominal: S6 = 0x00/0x1C, 32 clocks per CAN bit; 4 clocks per UART bit so
//! that the simulation keeps up) on a wired-AND bus with two harness
//! SJA1000 nodes (Linux `sja1000` driver sequences). Bytes from the master
//! go into the simulated UART as soon as it is free; bytes the UART sends
//! go to the master.
//!
//! Checked: the nodes receive python's four frames (standard, extended,
//! both remote) with the right identifier, DLC and data; the nodes' four
//! frames reach python, which checks them and prints them (its output is
//! asserted here too) and exits 0. The run is bounded by simulated clocks
//! and by a wall timeout that kills the child; no sleep is an assertion.

mod sja1000_util;
mod slcan_util;

use canstar_controller::frame::Frame;
use canstar_controller::slcan::SlcanParams;
use nix::fcntl::{fcntl, FcntlArg, OFlag};
use nix::pty::openpty;
use nix::sys::termios::{cfmakeraw, tcgetattr, tcsetattr, SetArg};
use slcan_util::*;
use std::io::Read;
use std::os::fd::{AsFd, AsRawFd};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const MAX_CYCLES: usize = 1_000_000;
const WALL: Duration = Duration::from_secs(240);

fn python_ready() {
    let out = Command::new("python3").arg("-c").arg("import can, serial").output();
    match out {
        Ok(o) if o.status.success() => {}
        Ok(o) => panic!(
            "python-can and pyserial are needed (python3 -m pip install python-can pyserial; scripts/test-all.sh installs them): {}",
            String::from_utf8_lossy(&o.stderr)
        ),
        Err(e) => panic!("python3 not found ({e}): install python3, python-can and pyserial"),
    }
}

#[test]
fn python_can_slcan_over_a_pty() {
    python_ready();
    let pty = openpty(None, None).expect("openpty");
    let mut t = tcgetattr(pty.slave.as_fd()).unwrap();
    cfmakeraw(&mut t);
    tcsetattr(pty.slave.as_fd(), SetArg::TCSANOW, &t).unwrap();
    let flags = OFlag::from_bits_truncate(fcntl(pty.master.as_fd(), FcntlArg::F_GETFL).unwrap());
    fcntl(pty.master.as_fd(), FcntlArg::F_SETFL(flags | OFlag::O_NONBLOCK)).unwrap();
    let path = nix::unistd::ttyname(pty.slave.as_fd()).expect("ttyname");
    let master = pty.master.as_raw_fd();

    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/slcan_pty_client.py");
    let mut child = Command::new("python3")
        .arg(script)
        .arg(&path)
        .arg(format!("{}", WALL.as_secs()))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn python3");
    let start = Instant::now();

    let (mut net, sim) = net_with_slcan(2, &SlcanParams::with_clocks_per_bit(16_000_000, 4));
    open_node(&mut net, 0, 0x00, 0x1C);
    open_node(&mut net, 1, 0x00, 0x1C);

    let from_nodes = [
        (0, Frame::data(false, 0x321, 4, &[0xDE, 0xAD, 0xBE, 0xEF])),
        (1, Frame::data(true, 0x10000001, 8, &[0x10, 0x11, 0x12, 0x13, 0x14, 0x15, 0x16, 0x17])),
        (0, Frame::remote(false, 0x055, 1)),
        (1, Frame::remote(true, 0x0ABCDEF1, 0)),
    ];
    let from_python = [
        Frame::data(false, 0x123, 8, &[1, 2, 3, 4, 5, 6, 7, 8]),
        Frame::data(true, 0x1ABCDEF0, 3, &[0xA5, 0x5A, 0x00]),
        Frame::remote(false, 0x7FF, 2),
        Frame::remote(true, 0x42, 0),
    ];

    let mut buf = [0u8; 256];
    let mut next_tx = 0;
    let mut status = None;
    let mut host_bytes = 0usize;
    let sim_start = Instant::now();
    while status.is_none() {
        if net.cycle > MAX_CYCLES || start.elapsed() > WALL {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "python-can run not finished within {} clocks / {:?}; nodes received {:?} / {:?}",
                net.cycle, WALL, net.drv[0].rx, net.drv[1].rx
            );
        }
        // pty master -> simulated UART (when its queue is empty: bytes go
        // in as soon as the line is free)
        if sim.borrow().host_idle() {
            let n = unsafe { libc::read(master, buf.as_mut_ptr() as *mut libc::c_void, 64) };
            if n > 0 {
                sim.borrow_mut().send(&buf[..n as usize]);
                host_bytes += n as usize;
            }
        }
        net.run(64);
        // simulated UART -> pty master
        let out: Vec<u8> = std::mem::take(&mut sim.borrow_mut().received);
        let mut off = 0;
        while off < out.len() {
            let n = unsafe { libc::write(master, out[off..].as_ptr() as *const libc::c_void, out.len() - off) };
            if n > 0 {
                off += n as usize;
            } else if start.elapsed() > WALL {
                break;
            }
        }
        // once both nodes have python's frames, they send theirs, one after
        // the other
        if net.drv[0].rx.len() >= from_python.len() && net.drv[1].rx.len() >= from_python.len() {
            if next_tx < from_nodes.len() && !net.drv[0].tx_busy && !net.drv[1].tx_busy {
                let (i, f) = &from_nodes[next_tx];
                net.xmit(*i, f);
                next_tx += 1;
            }
        }
        status = child.try_wait().unwrap();
    }
    let sim_secs = sim_start.elapsed().as_secs_f64();
    let mut stdout = String::new();
    let mut stderr = String::new();
    child.stdout.take().unwrap().read_to_string(&mut stdout).unwrap();
    child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
    eprintln!(
        "python-can run: {} clocks in {sim_secs:.1} s ({:.0} clocks/s, 3 controllers), {host_bytes} bytes from python\n{stdout}",
        net.cycle,
        net.cycle as f64 / sim_secs
    );
    let status = status.unwrap();
    assert!(status.success(), "python client failed ({status}):\nstdout:\n{stdout}\nstderr:\n{stderr}");
    // each node received python's frames, then the other node's
    let others = |i: usize| from_nodes.iter().filter(move |(n, _)| *n != i).map(|(_, f)| f.clone());
    let want0: Vec<Frame> = from_python.iter().cloned().chain(others(0)).collect();
    let want1: Vec<Frame> = from_python.iter().cloned().chain(others(1)).collect();
    assert_eq!(net.drv[0].rx, want0, "node 0");
    assert_eq!(net.drv[1].rx, want1, "node 1");
    let rx_lines: Vec<&str> = stdout.lines().filter(|l| l.starts_with("RX ")).collect();
    assert_eq!(
        rx_lines,
        [
            "RX 321 0 0 4 deadbeef",
            "RX 10000001 1 0 8 1011121314151617",
            "RX 55 0 1 1 ",
            "RX ABCDEF1 1 1 0 ",
        ]
    );
    assert!(stdout.lines().any(|l| l == "SENT") && stdout.lines().last() == Some("OK"), "{stdout}");
}
