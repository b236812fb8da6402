//! [`CanCore`]: the complete CAN 2.0A/B protocol controller of one node
//! (can-protocol.md; bare section numbers below refer to it).
//!
//! Wiring (all on one clock, synchronous reset):
//!
//! ```text
//!  rx ──► Synchroniser ──► BitTiming ──sample, busmon──► CanFsm ──► events, status
//!                              ▲   │                        │
//!                              │   └──► tx                  │
//!                              └──────── drive, hs_en ◄─────┘
//! ```
//!
//! - [`canstar_hdl::sync::Synchroniser`] brings RX into the clock domain
//!   (`sync_depth` flip-flops, 2 by default).
//! - [`canstar_hdl::btl::BitTiming`] does prescaling, segments, hard and
//!   re-synchronisation, sampling and the transmit points (§2, §3).
//! - [`crate::fsm::CanFsm`] is the bit-stream processor (§4–§14), which uses
//!   the shared destuffer and CRC-15 blocks.
//!
//! The RX latency `L_rx` of §1.5 is `sync_depth + canstar_hdl::btl::L_RX`
//! clocks ([`CanCore::l_rx`]).
//!
//! # Ports
//!
//! Inputs: `clock`; `reset` (synchronous; the timing fields are latched
//! while it is high); `rx`; timing `brp`, `prop`, `ph1`, `ph2`, `sjw` (value − 1)
//! and `triple`; mode bits `listen_only`, `self_test`, `single_shot`,
//! `host_recovery` and the `recover` strobe; the transmit request `tx_req`
//! with `tx_ide`, `tx_rtr`, `tx_id` (29 bits, standard ids in bits 10..0),
//! `tx_dlc`, `tx_data` (byte 0 in bits 63..56) and `tx_abort`. See
//! [`crate::fsm::CanFsm`] for the request handshake. The counter load
//! `cnt_load` with `tec_in` (9 bits, ≥ 256 = bus-off) and `rec_in`: on every
//! clock with `cnt_load` high TEC and REC take these values, with priority
//! over `reset` (see [`crate::fsm::CanFsm`]); tie it low when unused.
//!
//! Timing fields (value − 1): `brp` 7 bits (1..128 clocks per TQ), `prop`
//! 4 bits (PROP 1..16), `ph1` 3 bits (1..8), `ph2` 3 bits (1..8; 1 only
//! with BRP ≥ 2), `sjw` 2 bits (1..min(4, PH1), not bounded by PH2: C22); NTQ 8..25, as in
//! [`canstar_hdl::btl`] ([`CanCore::set_timing`] sets them from a
//! [`canstar_hdl::timing::BtlConfig`]).
//!
//! Generation-time options (constants of the design, not ports): the RX
//! synchroniser depth ([`CanCore::with_sync_depth`]) and the bit at which a
//! receiver counts a successful reception in REC ([`CanCore::with_rec_rule`],
//! [`RecRule`]: ISO by default, C13).
//!
//! Outputs: `tx`; 1-clock event strobes `tx_done`, `arb_lost`
//! (+`arb_lost_pos`), `error` (+`err_kind` mask of `ERRK_*`, `err_field`,
//! `err_pos`, `err_tx`), `rx_valid` (+`rx_ide`, `rx_rtr`, `rx_id`, `rx_dlc`,
//! `rx_data`, held until the next delivery); status `tec`, `rec`, `state`
//! (0 error-active, 1 error-passive, 2 bus-off), `err_warn`, `cfg_err`.
//!
//! Debug bundle (§15; no influence on behaviour): `dbg_busmon`, `dbg_sample`
//! (the bit timing's sample strobe), `dbg_tx_rqst`, `dbg_field` (FIELD code,
//! see [`crate::fsm`]; 0 = Reset while held in reset or on a configuration
//! error), `dbg_pos`, `dbg_stuff`, `dbg_role` (1 = transmitter), `dbg_events`
//! (event word, `EV_*` bits of [`crate::fsm`]), `dbg_runs` (completed
//! bus-off recovery runs), `dbg_hard_sync`, `dbg_resync`.
//!
//! # Per-bit trace (§18)
//!
//! On the clock where `dbg_sample` is high, `dbg_field`/`dbg_pos`/
//! `dbg_stuff`/`dbg_role` describe the bit being sampled, `dbg_busmon` is
//! its sampled level and `tx` the level the node drove. On the next clock
//! `dbg_events` (bit `EV_BIT` set) holds the bit's events and `tec`, `rec`,
//! `state` the values after processing it.

use crate::fsm::CanFsm;
use canstar_hdl::btl::BitTiming;
use canstar_hdl::sync::Synchroniser;
use rust_hdl::prelude::*;

/// Default depth of the RX synchroniser.
pub const SYNC_DEPTH: usize = 2;

/// When a receiver counts a successful reception in REC (can-protocol.md
/// C13, disagreements D1 and D2). The two standards deliver the same frames
/// and send the same flags; they differ only in the bit at which REC − 1
/// (or the restore to 127) is applied. A generation-time choice: a constant
/// of the design, not a port.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RecRule {
    /// At the ACK slot, once the receiver has read its own dominant ACK
    /// back (ISO 11898-1: "reception without error up to the ACK slot and
    /// the successful transmission of the ACK bit"). An error after it
    /// (ACK_Delimiter, End_Of_Frame 1..6) adds its +1 to the decremented
    /// value, and a dominant End_Of_Frame bit 7 changes nothing more:
    /// ISO 16845-1 7.6.7, 7.6.8, 7.6.16. The default.
    #[default]
    Iso,
    /// At a recessive End_Of_Frame bit 7 only; a dominant one leaves REC
    /// unchanged: the 1999 reference programs (formerr and emlcount,
    /// receiver step 4, and the sums of emlcount steps 9-11).
    Bosch1999,
}

/// The controller core (see the module documentation).
#[derive(LogicBlock)]
pub struct CanCore {
    pub clock: Signal<In, Clock>,
    pub reset: Signal<In, Bit>,
    pub rx: Signal<In, Bit>,
    pub brp: Signal<In, Bits<7>>,
    pub prop: Signal<In, Bits<4>>,
    pub ph1: Signal<In, Bits<3>>,
    pub ph2: Signal<In, Bits<3>>,
    pub sjw: Signal<In, Bits<2>>,
    pub triple: Signal<In, Bit>,
    pub listen_only: Signal<In, Bit>,
    pub self_test: Signal<In, Bit>,
    pub single_shot: Signal<In, Bit>,
    pub host_recovery: Signal<In, Bit>,
    pub recover: Signal<In, Bit>,
    pub tx_req: Signal<In, Bit>,
    pub tx_ide: Signal<In, Bit>,
    pub tx_rtr: Signal<In, Bit>,
    pub tx_id: Signal<In, Bits<29>>,
    pub tx_dlc: Signal<In, Bits<4>>,
    pub tx_data: Signal<In, Bits<64>>,
    pub tx_abort: Signal<In, Bit>,
    pub cnt_load: Signal<In, Bit>,
    pub tec_in: Signal<In, Bits<9>>,
    pub rec_in: Signal<In, Bits<8>>,

    pub tx: Signal<Out, Bit>,
    pub tx_done: Signal<Out, Bit>,
    pub arb_lost: Signal<Out, Bit>,
    pub arb_lost_pos: Signal<Out, Bits<6>>,
    pub error: Signal<Out, Bit>,
    pub err_kind: Signal<Out, Bits<5>>,
    pub err_field: Signal<Out, Bits<5>>,
    pub err_pos: Signal<Out, Bits<8>>,
    pub err_tx: Signal<Out, Bit>,
    pub rx_valid: Signal<Out, Bit>,
    pub rx_ide: Signal<Out, Bit>,
    pub rx_rtr: Signal<Out, Bit>,
    pub rx_id: Signal<Out, Bits<29>>,
    pub rx_dlc: Signal<Out, Bits<4>>,
    pub rx_data: Signal<Out, Bits<64>>,
    pub tec: Signal<Out, Bits<9>>,
    pub rec: Signal<Out, Bits<8>>,
    pub state: Signal<Out, Bits<2>>,
    pub err_warn: Signal<Out, Bit>,
    pub cfg_err: Signal<Out, Bit>,

    pub dbg_busmon: Signal<Out, Bit>,
    pub dbg_sample: Signal<Out, Bit>,
    pub dbg_tx_rqst: Signal<Out, Bit>,
    pub dbg_field: Signal<Out, Bits<5>>,
    pub dbg_pos: Signal<Out, Bits<8>>,
    pub dbg_stuff: Signal<Out, Bit>,
    pub dbg_role: Signal<Out, Bit>,
    pub dbg_events: Signal<Out, Bits<{ crate::fsm::EV_BITS }>>,
    pub dbg_runs: Signal<Out, Bits<8>>,
    pub dbg_hard_sync: Signal<Out, Bit>,
    pub dbg_resync: Signal<Out, Bit>,

    sync: Synchroniser,
    btl: BitTiming,
    fsm: CanFsm,
    l_hold: Signal<Local, Bit>,
    /// [`RecRule::Iso`] as 1.
    rec_iso: Constant<Bit>,
    /// The frame state machine's two-clock mode (the bit timing's `sample`
    /// strobes are at least 2 clocks apart).
    pipe: Constant<Bit>,
}

// Host-side readers of the outputs: `crate::view::CoreView`.

impl CanCore {
    /// A core with the default synchroniser depth ([`SYNC_DEPTH`]).
    pub fn new() -> Self {
        Self::with_sync_depth(SYNC_DEPTH)
    }

    /// A core with an RX synchroniser of `depth` (1 or 2) flip-flops.
    pub fn with_sync_depth(depth: usize) -> Self {
        CanCore {
            clock: Default::default(),
            reset: Default::default(),
            rx: Default::default(),
            brp: Default::default(),
            prop: Default::default(),
            ph1: Default::default(),
            ph2: Default::default(),
            sjw: Default::default(),
            triple: Default::default(),
            listen_only: Default::default(),
            self_test: Default::default(),
            single_shot: Default::default(),
            host_recovery: Default::default(),
            recover: Default::default(),
            tx_req: Default::default(),
            tx_ide: Default::default(),
            tx_rtr: Default::default(),
            tx_id: Default::default(),
            tx_dlc: Default::default(),
            tx_data: Default::default(),
            tx_abort: Default::default(),
            cnt_load: Default::default(),
            tec_in: Default::default(),
            rec_in: Default::default(),
            tx: Default::default(),
            tx_done: Default::default(),
            arb_lost: Default::default(),
            arb_lost_pos: Default::default(),
            error: Default::default(),
            err_kind: Default::default(),
            err_field: Default::default(),
            err_pos: Default::default(),
            err_tx: Default::default(),
            rx_valid: Default::default(),
            rx_ide: Default::default(),
            rx_rtr: Default::default(),
            rx_id: Default::default(),
            rx_dlc: Default::default(),
            rx_data: Default::default(),
            tec: Default::default(),
            rec: Default::default(),
            state: Default::default(),
            err_warn: Default::default(),
            cfg_err: Default::default(),
            dbg_busmon: Default::default(),
            dbg_sample: Default::default(),
            dbg_tx_rqst: Default::default(),
            dbg_field: Default::default(),
            dbg_pos: Default::default(),
            dbg_stuff: Default::default(),
            dbg_role: Default::default(),
            dbg_events: Default::default(),
            dbg_runs: Default::default(),
            dbg_hard_sync: Default::default(),
            dbg_resync: Default::default(),
            sync: Synchroniser::new(depth),
            btl: Default::default(),
            fsm: CanFsm::new(),
            l_hold: Default::default(),
            rec_iso: Constant::new(RecRule::default() == RecRule::Iso),
            pipe: Constant::new(true),
        }
    }

    /// The same core with the REC rule `rule` (C13).
    pub fn with_rec_rule(mut self, rule: RecRule) -> Self {
        self.rec_iso = Constant::new(rule == RecRule::Iso);
        self
    }

    /// RX latency in clocks (§1.5) of a core with synchroniser depth `depth`:
    /// from a change of `rx` to the clock on which `busmon` can show it.
    pub fn l_rx(depth: usize) -> usize {
        depth + canstar_hdl::btl::L_RX
    }

    /// Drive the timing inputs (`brp`, `prop`, `ph1`, `ph2`, `sjw`, `triple`)
    /// from `t` (they take effect under reset).
    pub fn set_timing(&mut self, t: &canstar_hdl::timing::BtlConfig) {
        let (brp, prop, ph1, ph2, sjw) = t.fields();
        self.brp.next = (brp as u64).into();
        self.prop.next = (prop as u64).into();
        self.ph1.next = (ph1 as u64).into();
        self.ph2.next = (ph2 as u64).into();
        self.sjw.next = (sjw as u64).into();
        self.triple.next = t.triple;
    }
}

impl Default for CanCore {
    fn default() -> Self {
        Self::new()
    }
}

impl Logic for CanCore {
    #[hdl_gen]
    fn update(&mut self) {
        // The protocol logic is held in reset while the timing is rejected.
        self.l_hold.next = self.reset.val() | self.btl.cfg_err.val();

        self.sync.clock.next = self.clock.val();
        self.sync.reset.next = self.reset.val();
        self.sync.d.next = self.rx.val();

        self.btl.clock.next = self.clock.val();
        self.btl.reset.next = self.reset.val();
        self.btl.brp.next = self.brp.val();
        self.btl.prop.next = self.prop.val();
        self.btl.ph1.next = self.ph1.val();
        self.btl.ph2.next = self.ph2.val();
        self.btl.sjw.next = self.sjw.val();
        self.btl.triple.next = self.triple.val();
        self.btl.rx.next = self.sync.q.val();
        self.btl.drive.next = self.fsm.drive.val();
        self.btl.hs_en.next = self.fsm.hs_en.val();

        self.fsm.clock.next = self.clock.val();
        self.fsm.reset.next = self.l_hold.val();
        self.fsm.sample.next = self.btl.sample.val();
        self.fsm.busmon.next = self.btl.busmon.val();
        self.fsm.listen_only.next = self.listen_only.val();
        self.fsm.self_test.next = self.self_test.val();
        self.fsm.single_shot.next = self.single_shot.val();
        self.fsm.host_recovery.next = self.host_recovery.val();
        self.fsm.recover.next = self.recover.val();
        self.fsm.rec_iso.next = self.rec_iso.val();
        self.fsm.pipe.next = self.pipe.val();
        self.fsm.tx_req.next = self.tx_req.val();
        self.fsm.tx_ide.next = self.tx_ide.val();
        self.fsm.tx_rtr.next = self.tx_rtr.val();
        self.fsm.tx_id.next = self.tx_id.val();
        self.fsm.tx_dlc.next = self.tx_dlc.val();
        self.fsm.tx_data.next = self.tx_data.val();
        self.fsm.tx_abort.next = self.tx_abort.val();
        self.fsm.cnt_load.next = self.cnt_load.val();
        self.fsm.tec_in.next = self.tec_in.val();
        self.fsm.rec_in.next = self.rec_in.val();

        self.tx.next = self.btl.tx.val();
        self.tx_done.next = self.fsm.tx_done.val();
        self.arb_lost.next = self.fsm.arb_lost.val();
        self.arb_lost_pos.next = self.fsm.arb_lost_pos.val();
        self.error.next = self.fsm.error.val();
        self.err_kind.next = self.fsm.err_kind.val();
        self.err_field.next = self.fsm.err_field.val();
        self.err_pos.next = self.fsm.err_pos.val();
        self.err_tx.next = self.fsm.err_tx.val();
        self.rx_valid.next = self.fsm.rx_valid.val();
        self.rx_ide.next = self.fsm.rx_ide.val();
        self.rx_rtr.next = self.fsm.rx_rtr.val();
        self.rx_id.next = self.fsm.rx_id.val();
        self.rx_dlc.next = self.fsm.rx_dlc.val();
        self.rx_data.next = self.fsm.rx_data.val();
        self.tec.next = self.fsm.tec.val();
        self.rec.next = self.fsm.rec.val();
        self.state.next = self.fsm.state.val();
        self.err_warn.next = self.fsm.err_warn.val();
        self.cfg_err.next = self.btl.cfg_err.val();

        self.dbg_busmon.next = self.btl.busmon.val();
        self.dbg_sample.next = self.btl.sample.val();
        self.dbg_tx_rqst.next = self.fsm.tx_rqst.val();
        self.dbg_field.next = self.fsm.field.val();
        if self.l_hold.val() {
            self.dbg_field.next = 0.into();
        }
        self.dbg_pos.next = self.fsm.pos.val();
        self.dbg_stuff.next = self.fsm.stuff.val();
        self.dbg_role.next = self.fsm.role.val();
        self.dbg_events.next = self.fsm.events.val();
        self.dbg_runs.next = self.fsm.runs.val();
        self.dbg_hard_sync.next = self.btl.hard_sync.val();
        self.dbg_resync.next = self.btl.resync.val();
    }
}

canstar_hdl::impl_clocked!(CanCore);
