//! can-protocol.md §18 trace records: exact column format and a traced arbitration on the golden bus.

mod util;
use canstar_golden::trace::{msg_line, req_line, trace_line, HEADER};
use canstar_golden::{BitLabel, Event, FaultState, Field, Frame, ReqStatus, Role, StepOut};
use util::*;

#[allow(clippy::too_many_arguments)]
fn out(role: Role, field: Field, pos: u32, stuff: bool, smp: bool, drv: bool, tec: u16, ev: Vec<Event>) -> StepOut {
    StepOut {
        label: BitLabel { role, field, pos, stuff },
        sampled: smp,
        drove: drv,
        next_drive: true,
        tec,
        rec: 0,
        state: FaultState::ErrorActive,
        events: ev,
        req: vec![],
    }
}

/// The example lines of can-protocol.md §18 are reproduced character for character.
#[test]
fn trace_line_matches_spec_example_exactly() {
    assert_eq!(HEADER, "# t_ns   node field             pos stf smp drv tec rec st event");
    assert_eq!(
        trace_line(24800, "G1", &out(Role::Tx, Field::Identifier, 8, false, D, D, 8, vec![])),
        " 24800   G1   Tx_Identifier       8  -   0   0    8   0 EA -"
    );
    assert_eq!(
        trace_line(25800, "G1", &out(Role::Tx, Field::Identifier, 9, false, D, R, 8, vec![Event::ArbLost(9)])),
        " 25800   G1   Tx_Identifier       9  -   0   1    8   0 EA ARB_LOST"
    );
    assert_eq!(
        trace_line(26800, "G1", &out(Role::Rx, Field::Identifier, 10, false, D, R, 8, vec![])),
        " 26800   G1   Rx_Identifier      10  -   0   1    8   0 EA -"
    );
    assert_eq!(
        trace_line(29800, "G2", &out(Role::Tx, Field::RtrBit, 1, true, R, R, 0, vec![])),
        " 29800   G2   Tx_RTR_Bit          1  S   1   1    0   0 EA -"
    );
    assert_eq!(
        trace_line(1600, "D1", &out(Role::None, Field::BusIdle, 3, false, R, R, 0, vec![Event::Error(canstar_golden::ErrorKind::Stuff), Event::Aef, Event::Daf(3)])),
        "  1600   D1   Bus_Idle            3  -   1   1    0   0 EA STUFF_ERR,AEF,DAF=3"
    );
}

#[test]
fn msg_and_req_records() {
    assert_eq!(
        msg_line(5000, "G2", &Frame::ext_data(0x1ABCDEF, 2, &[0x0A, 0xFF])),
        "  5000   G2   MSG ext data id=0x1abcdef dlc=2 data=0aff"
    );
    assert_eq!(msg_line(7, "G1", &Frame::std_remote(0x12, 9)), "     7   G1   MSG std remote id=0x12 dlc=9 data=");
    assert_eq!(req_line(100, "G1", ReqStatus::Transmitting), "   100   G1   REQ transmitting");
}

/// A traced contest: one line per node per bit, sorted by (t_ns, node), ARB_LOST on G1's
/// line at Identifier 9 and Rx_ labels afterwards, MSG records for both deliveries, REQ
/// records for the request status changes.
#[test]
fn bus_trace_of_an_arbitration_contest() {
    let mut b = idle_bus(2);
    let t0 = b.bit;
    b.enable_trace();
    b.nodes[0].request(Frame::std_data(0x127, 0, &[]));
    b.nodes[1].request(Frame::std_data(0x123, 0, &[]));
    run_to_tx_ok(&mut b, 1, 200);
    run_to_tx_ok(&mut b, 0, 200);
    let tr = b.trace.clone().unwrap();
    assert_eq!(tr[0], HEADER);
    let bits: Vec<&String> = tr.iter().filter(|l| !l.contains(" MSG ") && !l.contains(" REQ ") && !l.starts_with('#')).collect();
    assert_eq!(bits.len() as u64, 2 * (b.bit - t0));
    // sorted by time then node
    let key = |l: &str| {
        let mut it = l.split_whitespace();
        (it.next().unwrap().parse::<u64>().unwrap(), it.next().unwrap().to_string())
    };
    for w in bits.windows(2) {
        assert!(key(w[0]) < key(w[1]), "{} / {}", w[0], w[1]);
    }
    let lost = bits.iter().find(|l| l.ends_with("ARB_LOST")).unwrap();
    let cols: Vec<&str> = lost.split_whitespace().collect();
    assert_eq!(&cols[1..7], &["G1", "Tx_Identifier", "9", "-", "0", "1"]);
    let t_lost = key(lost).0;
    let next = bits.iter().find(|l| key(l) == (t_lost + 1000, "G1".to_string())).unwrap();
    assert!(next.contains("Rx_Identifier      10"));
    assert!(tr.iter().any(|l| l.contains("G1   MSG std data id=0x123 dlc=0")));
    assert!(tr.iter().any(|l| l.contains("G2   MSG std data id=0x127 dlc=0")));
    assert!(tr.iter().any(|l| l.contains("G1   REQ transmitting")));
    assert!(tr.iter().any(|l| l.contains("G1   REQ done")));
    // every bit line has 10 or 11 whitespace-separated columns and a known state
    for l in &bits {
        let c: Vec<&str> = l.split_whitespace().collect();
        assert_eq!(c.len(), 11, "{l}");
        assert!(["EA", "EP", "BO"].contains(&c[9]));
    }
}
